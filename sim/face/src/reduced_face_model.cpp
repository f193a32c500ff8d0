#include "facectl/face/reduced_face_model.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>

#include "facectl/face/input_error.hpp"

namespace facectl::face {
namespace {

int feature_count(std::size_t muscles) { return static_cast<int>(3 * muscles + 9); }

void fill_features(std::span<const double> c, double pitch, double yaw, double prot,
                   Eigen::Ref<Eigen::VectorXd> f) {
  const std::size_t n = c.size();
  for (std::size_t i = 0; i < n; ++i) {
    f[i] = c[i];
    f[n + i] = c[i] * c[i];
    f[2 * n + i] = c[i] * pitch;
  }
  // Jaw terms in scaled units (deg-like and mm-like) so the fit is well conditioned.
  const double p = pitch * 10, y = yaw * 10, t = prot * 100;
  const std::size_t j = 3 * n;
  f[j + 0] = p;
  f[j + 1] = y;
  f[j + 2] = t;
  f[j + 3] = p * p;
  f[j + 4] = y * y;
  f[j + 5] = t * t;
  f[j + 6] = p * y;
  f[j + 7] = p * t;
  f[j + 8] = y * t;
}

}  // namespace

ReducedFaceWorkspace make_reduced_workspace(const ReducedFaceModel& m) {
  return {Eigen::VectorXd::Zero(m.feature_count())};
}

void evaluate(const ReducedFaceModel& m, ReducedFaceWorkspace& w,
              std::span<const double> contractions, double pitch_rad, double yaw_rad,
              double protrusion_m, std::span<double> out) {
  fill_features(contractions, pitch_rad, yaw_rad, protrusion_m, w.features);
  Eigen::Map<Eigen::VectorXd> o(out.data(), static_cast<Eigen::Index>(out.size()));
  o.noalias() = m.coefficients * w.features;
}

std::vector<ReducedSample> random_samples(const HeadSpec& head, const ReduceOptions& o, int n,
                                          unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  constexpr double kDeg = std::numbers::pi / 180;
  std::vector<ReducedSample> out;
  for (int k = 0; k < n; ++k) {
    ReducedSample s;
    s.contractions.assign(head.commanded.size(), 0.0);
    for (double& c : s.contractions) {
      const bool active = u(rng) < o.active_probability;
      const double v = u(rng) * o.max_contraction;
      c = active ? v : 0.0;
    }
    s.jaw.pitch_rad = (-4 + 22 * u(rng)) * kDeg;
    s.jaw.yaw_rad = (-5 + 10 * u(rng)) * kDeg;
    s.jaw.protrusion_m = 0.008 * u(rng);
    out.push_back(std::move(s));
  }
  return out;
}

std::vector<double> full_model_response(const FaceModel& m, FaceData& d,
                                        const std::vector<int>& cps, const ReducedSample& s,
                                        int frames) {
  reset_face_data(m, d);
  FaceInput in;
  in.contractions = s.contractions;
  in.jaw = s.jaw;
  for (int f = 0; f < frames; ++f) step_face(m, d, in);
  std::vector<double> out;
  for (int l : cps) {
    const Vec3 v = landmark_position(m, d.skin_x, l) - landmark_position(m, m.skin.v, l);
    out.insert(out.end(), {v.x(), v.y(), v.z()});
  }
  return out;
}

ReducedFaceModel build_reduced_model(const FaceModel& full, const ReduceOptions& o,
                                     ReduceReport* report) {
  ReducedFaceModel r;
  r.muscles = full.spec.commanded;
  r.control_points = full.spec.control_points;
  std::vector<int> cps;
  for (const auto& n : r.control_points) cps.push_back(full.landmark_index(n));
  const int F = feature_count(r.muscles.size());
  const int P = 3 * static_cast<int>(cps.size());
  FaceData d = make_face_data(full);
  auto collect = [&](const std::vector<ReducedSample>& set, Eigen::MatrixXd& X, Eigen::MatrixXd& Y) {
    X.resize(static_cast<Eigen::Index>(set.size()), F);
    Y.resize(static_cast<Eigen::Index>(set.size()), P);
    for (std::size_t k = 0; k < set.size(); ++k) {
      Eigen::VectorXd f(F);
      fill_features(set[k].contractions, set[k].jaw.pitch_rad, set[k].jaw.yaw_rad,
                    set[k].jaw.protrusion_m, f);
      X.row(static_cast<Eigen::Index>(k)) = f.transpose();
      const std::vector<double> y = full_model_response(full, d, cps, set[k], o.frames);
      for (int j = 0; j < P; ++j) Y(static_cast<Eigen::Index>(k), j) = y[j];
    }
  };
  Eigen::MatrixXd Xtr, Ytr, Xte, Yte;
  collect(random_samples(full.spec, o, o.train_samples, o.seed), Xtr, Ytr);
  // Ridge-regularised normal equations, solved by Cholesky (LDLT).
  const Eigen::MatrixXd A = Xtr.transpose() * Xtr + o.ridge * Eigen::MatrixXd::Identity(F, F);
  const Eigen::MatrixXd B = Xtr.transpose() * Ytr;
  r.coefficients = A.ldlt().solve(B).transpose();
  if (report) {
    report->train_samples = o.train_samples;
    report->test_samples = o.test_samples;
    const Eigen::MatrixXd Etr = Xtr * r.coefficients.transpose() - Ytr;
    report->train_rms_mm = 1e3 * std::sqrt(Etr.squaredNorm() / (static_cast<double>(Etr.rows() * Etr.cols()) / 3.0));
    if (o.test_samples > 0) {
      collect(random_samples(full.spec, o, o.test_samples, o.seed + 7919), Xte, Yte);
      const Eigen::MatrixXd E = Xte * r.coefficients.transpose() - Yte;
      double sum = 0, worst = 0;
      for (Eigen::Index k = 0; k < E.rows(); ++k)
        for (Eigen::Index j = 0; j + 2 < E.cols(); j += 3) {
          const double e2 = E(k, j) * E(k, j) + E(k, j + 1) * E(k, j + 1) + E(k, j + 2) * E(k, j + 2);
          sum += e2;
          worst = std::max(worst, std::sqrt(e2));
        }
      // RMS and max of the per-point 3D error over all held-out samples and points.
      report->test_rms_mm = 1e3 * std::sqrt(sum / static_cast<double>(E.rows() * (E.cols() / 3)));
      report->test_max_mm = 1e3 * worst;
    }
  }
  return r;
}

void save_reduced_model(const ReducedFaceModel& m, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw InputError(path + ": cannot open file for writing");
  out << "facectl-reduced-face 1\n";
  out << "muscles " << m.muscles.size();
  for (const auto& s : m.muscles) out << ' ' << s;
  out << "\ncontrol_points " << m.control_points.size();
  for (const auto& s : m.control_points) out << ' ' << s;
  out << "\ncoefficients " << m.coefficients.rows() << ' ' << m.coefficients.cols() << '\n';
  out.precision(17);
  for (Eigen::Index i = 0; i < m.coefficients.rows(); ++i) {
    for (Eigen::Index j = 0; j < m.coefficients.cols(); ++j) out << (j ? " " : "") << m.coefficients(i, j);
    out << '\n';
  }
  if (!out) throw InputError(path + ": write failed");
}

ReducedFaceModel load_reduced_model(const std::string& path, const HeadSpec& head) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open file");
  ReducedFaceModel m;
  std::string line;
  int ln = 0;
  auto next = [&](const char* what) {
    if (!std::getline(in, line)) throw InputError(path, ln + 1, 0, std::string("expected ") + what + ", found end of file");
    ++ln;
    return std::istringstream(line);
  };
  {
    auto s = next("the header 'facectl-reduced-face 1'");
    std::string tag;
    int v = 0;
    if (!(s >> tag >> v) || tag != "facectl-reduced-face" || v != 1)
      throw InputError(path, ln, 0, "expected 'facectl-reduced-face 1', found '" + line + "'");
  }
  auto names = [&](const char* key, std::vector<std::string>& out) {
    auto s = next(key);
    std::string tag;
    std::size_t n = 0;
    if (!(s >> tag >> n) || tag != key) throw InputError(path, ln, 0, std::string("expected '") + key + " N ...', found '" + line + "'");
    out.resize(n);
    for (auto& x : out)
      if (!(s >> x)) throw InputError(path, ln, 0, std::string("expected ") + std::to_string(n) + " names after '" + key + "'");
  };
  names("muscles", m.muscles);
  if (m.muscles != head.commanded)
    throw InputError(path, ln, 0, "expected the muscles of head.yaml in order, found a different list (rebuild with `facectl face reduce`)");
  names("control_points", m.control_points);
  auto s = next("'coefficients ROWS COLS'");
  std::string tag;
  Eigen::Index rows = 0, cols = 0;
  if (!(s >> tag >> rows >> cols) || tag != "coefficients" ||
      rows != 3 * static_cast<Eigen::Index>(m.control_points.size()) ||
      cols != feature_count(m.muscles.size()))
    throw InputError(path, ln, 0, "expected 'coefficients " + std::to_string(3 * m.control_points.size()) + " " +
                                      std::to_string(feature_count(m.muscles.size())) + "', found '" + line + "'");
  m.coefficients.resize(rows, cols);
  for (Eigen::Index i = 0; i < rows; ++i) {
    auto r = next("a row of coefficients");
    for (Eigen::Index j = 0; j < cols; ++j)
      if (!(r >> m.coefficients(i, j)))
        throw InputError(path, ln, 0, "expected " + std::to_string(cols) + " numbers, found fewer or a non-number");
  }
  return m;
}

}  // namespace facectl::face
