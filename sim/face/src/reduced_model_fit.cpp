#include "facectl/face/reduced_model_fit.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>

#include "control/envelope/mandible_envelope.hpp"
#include "control/units.hpp"
#include "facectl/face/input_error.hpp"

namespace facectl::face {

std::vector<ReducedSample> random_samples(const HeadSpec& head, const ReduceOptions& o, int n,
                                          unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<ReducedSample> out;
  for (int k = 0; k < n; ++k) {
    ReducedSample s;
    s.contractions.assign(head.commanded.size(), 0.0);
    for (double& c : s.contractions) {
      const bool active = u(rng) < o.active_probability;
      const double v = u(rng) * o.max_contraction;
      c = active ? v : 0.0;
    }
    // Uniform over the mandible's joint limits.
    s.jaw.pitch_rad = (kJawPitchMinDeg + (kJawPitchMaxDeg - kJawPitchMinDeg) * u(rng)) * kDeg;
    s.jaw.yaw_rad = (-kJawYawMaxDeg + 2 * kJawYawMaxDeg * u(rng)) * kDeg;
    s.jaw.protrusion_m = kJawProtrusionMaxMm * 1e-3 * u(rng);
    out.push_back(std::move(s));
  }
  return out;
}

std::vector<double> full_model_response(const FaceModel& m, FaceData& d,
                                        const std::vector<int>& cps, const ReducedSample& s,
                                        const SteadyStateOptions& steady,
                                        SteadyStateResult* settled) {
  reset_face_data(m, d);
  FaceInput in;
  in.contractions = s.contractions;
  in.jaw = s.jaw;
  const SteadyStateResult r = run_to_steady_state(m, d, in, steady);
  if (settled) *settled = r;
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
  ReduceReport counts;
  auto response = [&](const ReducedSample& s) {
    SteadyStateResult settled;
    std::vector<double> y = full_model_response(full, d, cps, s, o.steady, &settled);
    counts.unsettled_runs += !settled.converged;
    counts.worst_residual_mm = std::max(counts.worst_residual_mm, settled.residual_mm);
    return y;
  };

  // Which muscles move which control point: one full-model run per muscle alone.
  std::vector<std::vector<char>> moves(M, std::vector<char>(P, 0));
  for (int i = 0; i < M; ++i) {
    ReducedSample s;
    s.contractions.assign(M, 0.0);
    s.contractions[i] = 0.6;
    const std::vector<double> y = response(s);
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
  const int F = reduced_feature_count(r.muscles.size(), r.pairs.size());
  // Columns used by control point p: its muscles' terms, the jaw terms, its pairs.
  std::vector<std::vector<int>> cols(P);
  for (int p = 0; p < P; ++p) {
    for (int i = 0; i < M; ++i)
      if (moves[i][p])
        for (int k = 0; k < static_cast<int>(kFeaturesPerMuscle); ++k) cols[p].push_back(k * M + i);
    const int jaw = static_cast<int>(kFeaturesPerMuscle) * M;
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
      const std::vector<double> y = response(set[k]);
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
    report->unsettled_runs = counts.unsettled_runs;
    report->worst_residual_mm = counts.worst_residual_mm;
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
    // Bounded before allocating: a count is checked against what the line can hold.
    if (n > line.size() / 2)
      throw InputError(
          path, ln, 0,
          std::string("'") + key + " " + std::to_string(n) + "': more names than the line holds");
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
    const std::size_t most = m.muscles.size() * (m.muscles.size() - 1) / 2;
    if (n > most)
      throw InputError(path, ln, 0,
                       "'pairs " + std::to_string(n) + "': expected at most " +
                           std::to_string(most) + ", the pairs of " +
                           std::to_string(m.muscles.size()) + " muscles");
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
      cols != reduced_feature_count(m.muscles.size(), m.pairs.size()))
    throw InputError(path, ln, 0,
                     "expected 'coefficients " + std::to_string(3 * m.control_points.size()) + " " +
                         std::to_string(reduced_feature_count(m.muscles.size(), m.pairs.size())) +
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
