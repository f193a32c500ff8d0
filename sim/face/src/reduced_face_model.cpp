#include "facectl/face/reduced_face_model.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>

#include "facectl/face/input_error.hpp"

namespace facectl::face {
namespace {

constexpr std::size_t kPerMuscle = 6;  // c, c², c³, c·pitch, c·yaw, c·protrusion
// Jaw terms in scaled units (deg-like and mm-like) so the fit is well conditioned.
constexpr double kPitchScale = 10, kYawScale = 10, kProtrusionScale = 100;

int feature_count(std::size_t muscles, std::size_t pairs) {
  return static_cast<int>(kPerMuscle * muscles + 9 + pairs);
}

// The jaw variables in the fit's units, for fill_features and fill_feature_variables.
std::array<double, 3> scaled_jaw(double pitch, double yaw, double prot) {
  return {pitch * kPitchScale, yaw * kYawScale, prot * kProtrusionScale};
}

void fill_features(std::span<const double> c, double pitch, double yaw, double prot,
                   const std::vector<std::array<int, 2>>& pairs, Eigen::Ref<Eigen::VectorXd> f) {
  const std::size_t n = c.size();
  const auto [p, y, t] = scaled_jaw(pitch, yaw, prot);
  for (std::size_t i = 0; i < n; ++i) {
    f[i] = c[i];
    f[n + i] = c[i] * c[i];
    f[2 * n + i] = c[i] * c[i] * c[i];
    f[3 * n + i] = c[i] * p;
    f[4 * n + i] = c[i] * y;
    f[5 * n + i] = c[i] * t;
  }
  const std::size_t j = kPerMuscle * n;
  f[j + 0] = p;
  f[j + 1] = y;
  f[j + 2] = t;
  f[j + 3] = p * p;
  f[j + 4] = y * y;
  f[j + 5] = t * t;
  f[j + 6] = p * y;
  f[j + 7] = p * t;
  f[j + 8] = y * t;
  for (std::size_t k = 0; k < pairs.size(); ++k) f[j + 9 + k] = c[pairs[k][0]] * c[pairs[k][1]];
}

}  // namespace

// Column for column as fill_features, whose products these are in the same order.
std::array<int, 3> feature_factors(const ReducedFaceModel& m, int column) {
  const int n = static_cast<int>(m.muscles.size());
  const int pitch = n, yaw = n + 1, prot = n + 2, one = n + 3;
  const int per_muscle = static_cast<int>(kPerMuscle) * n;
  if (column < 0 || column >= feature_count(m.muscles.size(), m.pairs.size()))
    throw std::out_of_range("reduced face model: no feature column " + std::to_string(column));
  if (column < per_muscle) {
    const int i = column % n;
    const std::array<std::array<int, 3>, kPerMuscle> kinds = {
        {{i, one, one}, {i, i, one}, {i, i, i}, {i, pitch, one}, {i, yaw, one}, {i, prot, one}}};
    return kinds[static_cast<std::size_t>(column / n)];
  }
  const int j = column - per_muscle;
  if (j < 9) {
    const std::array<std::array<int, 3>, 9> jaw = {{{pitch, one, one},
                                                    {yaw, one, one},
                                                    {prot, one, one},
                                                    {pitch, pitch, one},
                                                    {yaw, yaw, one},
                                                    {prot, prot, one},
                                                    {pitch, yaw, one},
                                                    {pitch, prot, one},
                                                    {yaw, prot, one}}};
    return jaw[static_cast<std::size_t>(j)];
  }
  const auto [a, b] = m.pairs[static_cast<std::size_t>(j - 9)];
  return {a, b, one};
}

void fill_feature_variables(std::span<const double> c, double pitch, double yaw, double prot,
                            std::span<double> v) {
  const std::size_t n = c.size();
  std::copy(c.begin(), c.end(), v.begin());
  const std::array<double, 3> jaw = scaled_jaw(pitch, yaw, prot);
  std::copy(jaw.begin(), jaw.end(), v.begin() + static_cast<std::ptrdiff_t>(n));
  v[n + 3] = 1.0;
}

// The symbolic twin of fill_features, column for column: keep the two in step (the
// drift guard in tests/unit/feature_monomials_test.cpp evaluates both on random inputs;
// feature_factors above is the other twin, tests/unit/feature_subset_test.cpp).
std::vector<Monomial> feature_monomials(const ReducedFaceModel& m) {
  const int n = static_cast<int>(m.muscles.size());
  const int pitch = n, yaw = n + 1, prot = n + 2;
  std::vector<Monomial> f(
      static_cast<std::size_t>(feature_count(m.muscles.size(), m.pairs.size())));
  auto set = [&](std::size_t column, double scale, std::vector<std::array<int, 2>> powers) {
    f[column] = {scale, std::move(powers)};
  };
  for (int i = 0; i < n; ++i) {
    const std::size_t k = static_cast<std::size_t>(i), N = static_cast<std::size_t>(n);
    set(k, 1, {{i, 1}});
    set(N + k, 1, {{i, 2}});
    set(2 * N + k, 1, {{i, 3}});
    set(3 * N + k, kPitchScale, {{i, 1}, {pitch, 1}});
    set(4 * N + k, kYawScale, {{i, 1}, {yaw, 1}});
    set(5 * N + k, kProtrusionScale, {{i, 1}, {prot, 1}});
  }
  const std::size_t j = kPerMuscle * m.muscles.size();
  set(j + 0, kPitchScale, {{pitch, 1}});
  set(j + 1, kYawScale, {{yaw, 1}});
  set(j + 2, kProtrusionScale, {{prot, 1}});
  set(j + 3, kPitchScale * kPitchScale, {{pitch, 2}});
  set(j + 4, kYawScale * kYawScale, {{yaw, 2}});
  set(j + 5, kProtrusionScale * kProtrusionScale, {{prot, 2}});
  set(j + 6, kPitchScale * kYawScale, {{pitch, 1}, {yaw, 1}});
  set(j + 7, kPitchScale * kProtrusionScale, {{pitch, 1}, {prot, 1}});
  set(j + 8, kYawScale * kProtrusionScale, {{yaw, 1}, {prot, 1}});
  for (std::size_t k = 0; k < m.pairs.size(); ++k) {
    const auto [a, b] = m.pairs[k];
    if (a == b)
      set(j + 9 + k, 1, {{a, 2}});
    else
      set(j + 9 + k, 1, {{std::min(a, b), 1}, {std::max(a, b), 1}});
  }
  return f;
}

double evaluate_monomial(const Monomial& m, std::span<const double> variables) {
  double v = m.coefficient;
  for (const auto& [var, power] : m.powers)
    for (int e = 0; e < power; ++e) v *= variables[static_cast<std::size_t>(var)];
  return v;
}

ReducedFaceWorkspace make_reduced_workspace(const ReducedFaceModel& m) {
  return {Eigen::VectorXd::Zero(m.feature_count())};
}

void evaluate_features(const ReducedFaceModel& m, ReducedFaceWorkspace& w,
                       std::span<const double> contractions, double pitch_rad, double yaw_rad,
                       double protrusion_m) {
  fill_features(contractions, pitch_rad, yaw_rad, protrusion_m, m.pairs, w.features);
}

void evaluate(const ReducedFaceModel& m, ReducedFaceWorkspace& w,
              std::span<const double> contractions, double pitch_rad, double yaw_rad,
              double protrusion_m, std::span<double> out) {
  evaluate_features(m, w, contractions, pitch_rad, yaw_rad, protrusion_m);
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
  const int M = static_cast<int>(r.muscles.size()), P = static_cast<int>(cps.size());
  FaceData d = make_face_data(full);

  // Which muscles move which control point: one full-model run per muscle alone.
  std::vector<std::vector<char>> moves(M, std::vector<char>(P, 0));
  for (int i = 0; i < M; ++i) {
    ReducedSample s;
    s.contractions.assign(M, 0.0);
    s.contractions[i] = 0.6;
    const std::vector<double> y = full_model_response(full, d, cps, s, o.frames);
    for (int p = 0; p < P; ++p)
      moves[i][p] = Vec3(y[3 * p], y[3 * p + 1], y[3 * p + 2]).norm() * 1e3 > o.relevance_mm;
  }
  for (int i = 0; i < M; ++i)
    for (int j = i + 1; j < M; ++j)
      for (int p = 0; p < P; ++p)
        if (moves[i][p] && moves[j][p]) {
          r.pairs.push_back({i, j});
          break;
        }
  const int F = feature_count(r.muscles.size(), r.pairs.size());
  // Columns used by control point p: its muscles' terms, the jaw terms, its pairs.
  std::vector<std::vector<int>> cols(P);
  for (int p = 0; p < P; ++p) {
    for (int i = 0; i < M; ++i)
      if (moves[i][p])
        for (int k = 0; k < static_cast<int>(kPerMuscle); ++k) cols[p].push_back(k * M + i);
    const int jaw = static_cast<int>(kPerMuscle) * M;
    for (int k = 0; k < 9; ++k) cols[p].push_back(jaw + k);
    for (std::size_t k = 0; k < r.pairs.size(); ++k)
      if (moves[r.pairs[k][0]][p] && moves[r.pairs[k][1]][p])
        cols[p].push_back(jaw + 9 + static_cast<int>(k));
  }

  auto collect = [&](const std::vector<ReducedSample>& set, Eigen::MatrixXd& X,
                     Eigen::MatrixXd& Y) {
    X.resize(static_cast<Eigen::Index>(set.size()), F);
    Y.resize(static_cast<Eigen::Index>(set.size()), 3 * P);
    for (std::size_t k = 0; k < set.size(); ++k) {
      Eigen::VectorXd f(F);
      fill_features(set[k].contractions, set[k].jaw.pitch_rad, set[k].jaw.yaw_rad,
                    set[k].jaw.protrusion_m, r.pairs, f);
      X.row(static_cast<Eigen::Index>(k)) = f.transpose();
      const std::vector<double> y = full_model_response(full, d, cps, set[k], o.frames);
      for (int j = 0; j < 3 * P; ++j) Y(static_cast<Eigen::Index>(k), j) = y[j];
    }
  };
  Eigen::MatrixXd Xtr, Ytr, Xte, Yte;
  collect(random_samples(full.spec, o, o.train_samples, o.seed), Xtr, Ytr);
  r.coefficients.setZero(3 * P, F);
  for (int p = 0; p < P; ++p) {
    // Ridge-regularised normal equations on this point's columns, solved by LDLT.
    const Eigen::Index n = static_cast<Eigen::Index>(cols[p].size());
    Eigen::MatrixXd Xp(Xtr.rows(), n);
    for (Eigen::Index c = 0; c < n; ++c) Xp.col(c) = Xtr.col(cols[p][c]);
    const Eigen::MatrixXd A = Xp.transpose() * Xp + o.ridge * Eigen::MatrixXd::Identity(n, n);
    const Eigen::MatrixXd B = Xp.transpose() * Ytr.middleCols(3 * p, 3);
    const Eigen::MatrixXd W = A.ldlt().solve(B);  // n × 3
    for (Eigen::Index c = 0; c < n; ++c)
      for (int k = 0; k < 3; ++k) r.coefficients(3 * p + k, cols[p][c]) = W(c, k);
  }
  if (report) {
    report->train_samples = o.train_samples;
    report->test_samples = o.test_samples;
    const Eigen::MatrixXd Etr = Xtr * r.coefficients.transpose() - Ytr;
    report->train_rms_mm =
        1e3 * std::sqrt(Etr.squaredNorm() / (static_cast<double>(Etr.rows() * Etr.cols()) / 3.0));
    if (o.test_samples > 0) {
      collect(random_samples(full.spec, o, o.test_samples, o.seed + 7919), Xte, Yte);
      const Eigen::MatrixXd E = Xte * r.coefficients.transpose() - Yte;
      double sum = 0, worst = 0;
      std::vector<double> errors;
      for (Eigen::Index k = 0; k < E.rows(); ++k)
        for (Eigen::Index j = 0; j + 2 < E.cols(); j += 3) {
          const double e2 =
              E(k, j) * E(k, j) + E(k, j + 1) * E(k, j + 1) + E(k, j + 2) * E(k, j + 2);
          sum += e2;
          worst = std::max(worst, std::sqrt(e2));
          errors.push_back(std::sqrt(e2));
        }
      std::sort(errors.begin(), errors.end());
      report->test_median_mm = 1e3 * errors[errors.size() / 2];
      report->test_p95_mm = 1e3 * errors[errors.size() * 95 / 100];
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
  out << "\npairs " << m.pairs.size();
  for (const auto& p : m.pairs) out << ' ' << p[0] << ' ' << p[1];
  out << "\ncoefficients " << m.coefficients.rows() << ' ' << m.coefficients.cols() << '\n';
  out.precision(17);
  for (Eigen::Index i = 0; i < m.coefficients.rows(); ++i) {
    for (Eigen::Index j = 0; j < m.coefficients.cols(); ++j)
      out << (j ? " " : "") << m.coefficients(i, j);
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
    if (!std::getline(in, line))
      throw InputError(path, ln + 1, 0, std::string("expected ") + what + ", found end of file");
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
    if (!(s >> tag >> n) || tag != key)
      throw InputError(path, ln, 0,
                       std::string("expected '") + key + " N ...', found '" + line + "'");
    out.resize(n);
    for (auto& x : out)
      if (!(s >> x))
        throw InputError(
            path, ln, 0,
            std::string("expected ") + std::to_string(n) + " names after '" + key + "'");
  };
  names("muscles", m.muscles);
  if (m.muscles != head.commanded)
    throw InputError(path, ln, 0,
                     "expected the muscles of head.yaml in order, found a different list (rebuild "
                     "with `facectl face reduce`)");
  names("control_points", m.control_points);
  {
    auto ps = next("'pairs N i j ...'");
    std::string tag;
    std::size_t n = 0;
    if (!(ps >> tag >> n) || tag != "pairs")
      throw InputError(path, ln, 0, "expected 'pairs N i j ...', found '" + line + "'");
    m.pairs.resize(n);
    for (auto& pr : m.pairs)
      if (!(ps >> pr[0] >> pr[1]) || pr[0] < 0 || pr[1] < 0 ||
          pr[0] >= static_cast<int>(m.muscles.size()) ||
          pr[1] >= static_cast<int>(m.muscles.size()))
        throw InputError(path, ln, 0,
                         "expected " + std::to_string(n) + " muscle index pairs in 0.." +
                             std::to_string(m.muscles.size() - 1));
  }
  auto s = next("'coefficients ROWS COLS'");
  std::string tag;
  Eigen::Index rows = 0, cols = 0;
  if (!(s >> tag >> rows >> cols) || tag != "coefficients" ||
      rows != 3 * static_cast<Eigen::Index>(m.control_points.size()) ||
      cols != feature_count(m.muscles.size(), m.pairs.size()))
    throw InputError(path, ln, 0,
                     "expected 'coefficients " + std::to_string(3 * m.control_points.size()) + " " +
                         std::to_string(feature_count(m.muscles.size(), m.pairs.size())) +
                         "', found '" + line + "'");
  m.coefficients.resize(rows, cols);
  for (Eigen::Index i = 0; i < rows; ++i) {
    auto r = next("a row of coefficients");
    for (Eigen::Index j = 0; j < cols; ++j)
      if (!(r >> m.coefficients(i, j)))
        throw InputError(
            path, ln, 0,
            "expected " + std::to_string(cols) + " numbers, found fewer or a non-number");
  }
  return m;
}

}  // namespace facectl::face
