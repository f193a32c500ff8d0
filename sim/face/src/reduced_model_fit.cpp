#include "facectl/face/reduced_model_fit.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

#include "control/envelope/mandible_envelope.hpp"
#include "control/units.hpp"
#include "facectl/face/file_digest.hpp"
#include "facectl/face/full_model_runs.hpp"
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
    if (o.random_eyelids)
      for (double& lid : s.eyelid_closure) lid = u(rng);
    out.push_back(std::move(s));
  }
  return out;
}

ReducedInput reduced_input(const ReducedSample& s) {
  ReducedInput in{s.contractions, s.jaw.pitch_rad, s.jaw.yaw_rad, s.jaw.protrusion_m};
  in.eyelid_closure[0] = s.eyelid_closure[0];
  in.eyelid_closure[1] = s.eyelid_closure[1];
  return in;
}

std::vector<double> full_model_response(const FaceModel& m, FaceData& d,
                                        const std::vector<int>& cps, const ReducedSample& s,
                                        const SteadyStateOptions& steady,
                                        SteadyStateResult* settled, bool teeth_collision) {
  reset_face_data(m, d);
  FaceInput in;
  in.teeth_collision = teeth_collision;
  in.contractions = s.contractions;
  in.jaw = s.jaw;
  in.eyelid_closure[0] = s.eyelid_closure[0];
  in.eyelid_closure[1] = s.eyelid_closure[1];
  const SteadyStateResult r = run_to_steady_state(m, d, in, steady);
  if (settled) *settled = r;
  std::vector<double> out;
  for (int l : cps) {
    const Vec3 v = landmark_position(m, d.skin_x, l) - landmark_position(m, m.skin.v, l);
    out.insert(out.end(), {v.x(), v.y(), v.z()});
  }
  return out;
}

std::vector<ReducedSample> training_samples(const HeadSpec& head, int n, unsigned seed,
                                            bool single_muscle_sweeps) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  // Each jaw DOF at its lower or upper limit 15% of the time each, so the envelope's faces
  // and corners are in the fit, and uniform between otherwise.
  auto dof = [&](double lo, double hi) {
    const double x = u(rng);
    return x < 0.15 ? lo : x < 0.3 ? hi : lo + (hi - lo) * u(rng);
  };
  const std::size_t M = head.commanded.size();
  std::vector<ReducedSample> out;
  for (int k = 0; k < n; ++k) {
    // Mixes from sparse to dense: 15%, 35%, 70% and all muscles active, c ~ U(0, 1).
    constexpr std::array<double, 4> kActive = {0.15, 0.35, 0.7, 1.0};
    const double active = kActive[static_cast<std::size_t>(k) % kActive.size()];
    ReducedSample s;
    s.contractions.assign(M, 0.0);
    for (double& c : s.contractions) {
      const bool on = u(rng) < active;
      const double v = u(rng);
      c = on ? v : 0.0;
    }
    s.jaw.pitch_rad = dof(kJawPitchMinDeg, kJawPitchMaxDeg) * kDeg;
    s.jaw.yaw_rad = dof(-kJawYawMaxDeg, kJawYawMaxDeg) * kDeg;
    s.jaw.protrusion_m = dof(0, kJawProtrusionMaxMm) * 1e-3;
    for (double& lid : s.eyelid_closure) lid = dof(0, 1);
    out.push_back(std::move(s));
  }
  // Each muscle alone over its range, half of them with the jaw at rest. The small
  // contractions hold the fit's slope at c = 0 to the full model's: without them a point a
  // muscle lifts could dip by a thousandth of a degree first, and verify's direction check
  // (every 1/64 of the range) refuses the model.
  for (std::size_t i = 0; i < (single_muscle_sweeps ? M : 0); ++i)
    for (double c : {0.03125, 0.0625, 0.125, 0.25, 0.5, 0.75, 1.0}) {
      ReducedSample s;
      s.contractions.assign(M, 0.0);
      s.contractions[i] = c;
      if (u(rng) < 0.5) {
        s.jaw.pitch_rad = dof(kJawPitchMinDeg, kJawPitchMaxDeg) * kDeg;
        s.jaw.yaw_rad = dof(-kJawYawMaxDeg, kJawYawMaxDeg) * kDeg;
        s.jaw.protrusion_m = dof(0, kJawProtrusionMaxMm) * 1e-3;
      }
      out.push_back(std::move(s));
    }
  // Each eyelid alone over its range.
  for (int side = 0; side < (single_muscle_sweeps ? 2 : 0); ++side)
    for (double c : {0.25, 0.5, 0.75, 1.0}) {
      ReducedSample s;
      s.contractions.assign(M, 0.0);
      s.eyelid_closure[side] = c;
      out.push_back(std::move(s));
    }
  return out;
}

namespace {

using Triple = std::array<int, 3>;

// The feature triples a control point moved by `muscles` and `lids` is fitted on: per
// muscle c, c², c³, c⁴ and c times each jaw variable; the jaw's full cubic; c_a·c_b, c_a²·c_b
// and c_a·c_b² for each pair; per lid l, and for the lids of `lid_points` (those that carry
// the point) l², l³ and l times each of the muscles too (the orbicularis oculi adds to a
// lid's closure, the brows carry it). Where the jaw moves the point (`jaw_point`), also
// c²·jaw and c·(each product of two jaw variables) per muscle: at the brows they gained
// nothing and made verify's proof six times as slow (docs/FACE_MODEL.md).
std::vector<Triple> point_features(const std::vector<int>& muscles, const std::vector<int>& lids,
                                   const std::vector<int>& lid_points, int n, bool jaw_point) {
  const int P = n, Y = n + 1, T = n + 2, one = constant_variable(static_cast<std::size_t>(n));
  std::vector<Triple> f;
  // The jaw's cubic: every product of up to three of pitch, yaw and protrusion.
  const std::array<int, 4> jaw = {P, Y, T, one};
  for (std::size_t a = 0; a < jaw.size(); ++a)
    for (std::size_t b = a; b < jaw.size(); ++b)
      for (std::size_t c = b; c < jaw.size(); ++c)
        if (jaw[a] != one) f.push_back({jaw[a], jaw[b], jaw[c]});
  for (int i : muscles) {
    const int sq = square_variable(static_cast<std::size_t>(n), i);
    for (const Triple& t : std::initializer_list<Triple>{{i, one, one},
                                                         {i, i, one},
                                                         {i, i, i},
                                                         {one, sq, sq},
                                                         {i, P, one},
                                                         {i, Y, one},
                                                         {i, T, one}})
      f.push_back(t);
    if (jaw_point)
      for (const Triple& t : std::initializer_list<Triple>{{i, i, P},
                                                           {i, i, Y},
                                                           {i, i, T},
                                                           {i, P, P},
                                                           {i, P, Y},
                                                           {i, P, T},
                                                           {i, Y, Y},
                                                           {i, Y, T},
                                                           {i, T, T}})
        f.push_back(t);
  }
  for (std::size_t x = 0; x < muscles.size(); ++x)
    for (std::size_t y = x + 1; y < muscles.size(); ++y) {
      const int a = std::min(muscles[x], muscles[y]), b = std::max(muscles[x], muscles[y]);
      for (const Triple& t : std::initializer_list<Triple>{{a, b, one}, {a, a, b}, {a, b, b}})
        f.push_back(t);
    }
  for (int l : lids) f.push_back({l, one, one});
  for (int l : lid_points) {
    f.push_back({l, l, one});
    f.push_back({l, l, l});
    for (int i : muscles) f.push_back({i, l, one});
  }
  return f;
}

}  // namespace

ReducedFaceModel build_reduced_model(const FaceModel& full, const ReduceOptions& o,
                                     ReduceReport* report) {
  ReducedFaceModel r;
  r.muscles = full.spec.commanded;
  r.control_points = full.spec.control_points;
  r.fitted_to = head_file_digests(full.spec);
  const std::vector<int> cps = full.landmark_indices(r.control_points);
  const int M = static_cast<int>(r.muscles.size()), P = static_cast<int>(cps.size());
  ReduceReport counts;
  // Every full-model run goes through here, a batch at a time, on o.threads threads.
  auto responses = [&](const std::vector<ReducedSample>& set) {
    FullModelRuns runs = run_full_model(full, cps, set, o.steady, o.threads);
    for (const SteadyStateResult& settled : runs.settled) {
      counts.unsettled_runs += settled.converged ? 0 : 1;
      counts.worst_residual_mm = std::max(counts.worst_residual_mm, settled.residual_mm);
    }
    return std::move(runs.responses);
  };
  auto at_rest = [M] {
    ReducedSample s;
    s.contractions.assign(static_cast<std::size_t>(M), 0.0);
    return s;
  };

  // Which muscles and lids move which control point: one full-model run per muscle alone
  // at 1, and per eyelid closed.
  std::vector<std::vector<int>> movers(static_cast<std::size_t>(P)), lids(movers.size());
  // Lids that move a point by more than kLidPointMm (the lid points themselves) enter as a
  // cubic coupled with its muscles; elsewhere a lid's small drag enters linearly: with the
  // cubic there too, verify's branch and bound over the inner-brow channels took four
  // times as long (measured before its Taylor form; docs/VERIFY.md).
  constexpr double kLidPointMm = 3;
  std::vector<std::vector<int>> lid_points(movers.size());
  std::vector<ReducedSample> probes;
  for (int i = 0; i < M; ++i) {
    probes.push_back(at_rest());
    probes.back().contractions[static_cast<std::size_t>(i)] = 1.0;
  }
  for (int side = 0; side < 2; ++side) {
    probes.push_back(at_rest());
    probes.back().eyelid_closure[side] = 1.0;
  }
  // The jaw at each corner of its envelope (below).
  for (int corner = 0; corner < 8; ++corner) {
    probes.push_back(at_rest());
    ReducedSample& s = probes.back();
    s.jaw.pitch_rad = ((corner & 1) ? kJawPitchMaxDeg : kJawPitchMinDeg) * kDeg;
    s.jaw.yaw_rad = ((corner & 2) ? kJawYawMaxDeg : -kJawYawMaxDeg) * kDeg;
    s.jaw.protrusion_m = (corner & 4) ? kJawProtrusionMaxMm * 1e-3 : 0.0;
  }
  const std::vector<std::vector<double>> probed = responses(probes);
  auto moved_mm = [&](std::size_t run, int p) {
    const std::vector<double>& y = probed[run];
    return Vec3(y[3 * p], y[3 * p + 1], y[3 * p + 2]).norm() * 1e3;
  };
  for (int i = 0; i < M; ++i)
    for (int p = 0; p < P; ++p)
      if (moved_mm(static_cast<std::size_t>(i), p) > o.relevance_mm)
        movers[static_cast<std::size_t>(p)].push_back(i);
  for (int side = 0; side < 2; ++side)
    for (int p = 0; p < P; ++p) {
      const double mm = moved_mm(static_cast<std::size_t>(M + side), p);
      const int lid = lid_variable(static_cast<std::size_t>(M), side);
      if (mm > o.relevance_mm) lids[static_cast<std::size_t>(p)].push_back(lid);
      if (mm > kLidPointMm) lid_points[static_cast<std::size_t>(p)].push_back(lid);
    }
  // Points the jaw moves by more than kJawPointMm at a corner of its envelope get its
  // couplings with the muscles (point_features). 0.4-0.5 mm at the brows, 2.5 mm and more
  // at the lips, nose and cheeks, 0 at the lids.
  constexpr double kJawPointMm = 1;
  std::vector<bool> jaw_point(movers.size(), false);
  for (int corner = 0; corner < 8; ++corner)
    for (int p = 0; p < P; ++p)
      if (moved_mm(static_cast<std::size_t>(M + 2 + corner), p) > kJawPointMm)
        jaw_point[static_cast<std::size_t>(p)] = true;
  // Each point's columns in the model's shared, deduplicated feature list.
  std::map<Triple, int> index;
  std::vector<std::vector<int>> cols(static_cast<std::size_t>(P));
  for (int p = 0; p < P; ++p)
    for (const Triple& t : point_features(
             movers[static_cast<std::size_t>(p)], lids[static_cast<std::size_t>(p)],
             lid_points[static_cast<std::size_t>(p)], M, jaw_point[static_cast<std::size_t>(p)])) {
      const auto [it, added] = index.emplace(t, static_cast<int>(r.features.size()));
      if (added) r.features.push_back(t);
      cols[static_cast<std::size_t>(p)].push_back(it->second);
    }
  const int F = static_cast<int>(r.features.size());

  auto collect = [&](const std::vector<ReducedSample>& set, Eigen::MatrixXd& X,
                     Eigen::MatrixXd& Y) {
    X.resize(static_cast<Eigen::Index>(set.size()), F);
    Y.resize(static_cast<Eigen::Index>(set.size()), 3 * P);
    Eigen::VectorXd v(variable_count(static_cast<std::size_t>(M))), f(F);
    const std::vector<std::vector<double>> ys = responses(set);
    for (std::size_t k = 0; k < set.size(); ++k) {
      fill_feature_variables(reduced_input(set[k]), std::span<double>(v.data(), v.size()));
      fill_features(std::span<const double>(v.data(), v.size()), r.features, f);
      X.row(static_cast<Eigen::Index>(k)) = f.transpose();
      for (int j = 0; j < 3 * P; ++j) Y(static_cast<Eigen::Index>(k), j) = ys[k][j];
    }
  };
  Eigen::MatrixXd Xtr, Ytr, Xte, Yte;
  collect(training_samples(full.spec, o.train_samples, o.seed, true), Xtr, Ytr);
  // The sweeps follow the mixes (training_samples): weight their rows.
  const double sweep = std::sqrt(o.sweep_weight);
  Xtr.bottomRows(Xtr.rows() - o.train_samples) *= sweep;
  Ytr.bottomRows(Ytr.rows() - o.train_samples) *= sweep;
  r.coefficients.setZero(3 * P, F);
  for (int p = 0; p < P; ++p) {
    // Ridge-regularised normal equations on this point's columns, solved by LDLT.
    const std::vector<int>& cp = cols[static_cast<std::size_t>(p)];
    const Eigen::Index n = static_cast<Eigen::Index>(cp.size());
    Eigen::MatrixXd Xp(Xtr.rows(), n);
    for (Eigen::Index c = 0; c < n; ++c) Xp.col(c) = Xtr.col(cp[static_cast<std::size_t>(c)]);
    const Eigen::MatrixXd A = Xp.transpose() * Xp + o.ridge * Eigen::MatrixXd::Identity(n, n);
    const Eigen::MatrixXd B = Xp.transpose() * Ytr.middleCols(3 * p, 3);
    const Eigen::MatrixXd W = A.ldlt().solve(B);  // n × 3
    for (Eigen::Index c = 0; c < n; ++c)
      for (int k = 0; k < 3; ++k)
        r.coefficients(3 * p + k, cp[static_cast<std::size_t>(c)]) = W(c, k);
  }
  if (report) {
    report->train_samples = static_cast<int>(Xtr.rows());
    Eigen::MatrixXd Etr = Xtr * r.coefficients.transpose() - Ytr;
    Etr.bottomRows(Etr.rows() - o.train_samples) /= sweep;  // each sample's own error
    report->train_rms_mm =
        1e3 * std::sqrt(Etr.squaredNorm() / (static_cast<double>(Etr.rows() * Etr.cols()) / 3.0));
    if (o.test_samples > 0) {
      // Mixes only: the single-muscle sweeps would repeat training inputs.
      collect(training_samples(full.spec, o.test_samples, o.seed + 7919, false), Xte, Yte);
      report->test_samples = static_cast<int>(Xte.rows());
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
  // The format separates tokens by spaces: a name with one could not be read back.
  auto check = [&](const std::string& name) {
    if (name.empty() || name.find_first_of(" \t\r\n") != std::string::npos)
      throw InputError(path + ": cannot write the name '" + name +
                       "': names in the reduced model may not be empty or hold whitespace");
  };
  for (const auto& [file, digest] : m.fitted_to) check(file);
  for (const auto& n : m.muscles) check(n);
  for (const auto& n : m.control_points) check(n);
  std::ofstream out(path);
  if (!out) throw InputError(path + ": cannot open file for writing");
  out << "facectl-reduced-face 4\n";
  out << "fitted_to " << m.fitted_to.size();
  for (const auto& [file, digest] : m.fitted_to) out << ' ' << file << ' ' << digest;
  out << "\nmuscles " << m.muscles.size();
  for (const auto& s : m.muscles) out << ' ' << s;
  out << "\ncontrol_points " << m.control_points.size();
  for (const auto& s : m.control_points) out << ' ' << s;
  out << "\nfeatures " << m.features.size();
  for (const auto& t : m.features) out << ' ' << t[0] << ' ' << t[1] << ' ' << t[2];
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
  constexpr const char* kRebuild = " (rebuild with `facectl face reduce`)";
  {
    auto s = next("the header 'facectl-reduced-face 4'");
    std::string tag;
    int v = 0;
    if (!(s >> tag) || tag != "facectl-reduced-face")
      throw InputError(path, ln, 0,
                       "expected 'facectl-reduced-face 4', found '" + line.substr(0, 80) + "'");
    if (!(s >> v) || v != 4)
      throw InputError(path, ln, 0,
                       "expected format 4, found '" + line.substr(0, 80) +
                           "': an older model has another form (format 3: no squared "
                           "contractions; 2: no eyelids; 1: no record of its head)" +
                           kRebuild);
  }
  // A line "key N" followed by N groups of `width` tokens; N is bounded by what the line holds.
  auto counted = [&](const char* key, std::size_t width, const char* what) {
    auto s = next(key);
    std::string tag;
    std::size_t n = 0;
    if (!(s >> tag >> n) || tag != key)
      throw InputError(
          path, ln, 0,
          std::string("expected '") + key + " N " + what + "', found '" + line.substr(0, 80) + "'");
    if (n > line.size() / (2 * width))
      throw InputError(path, ln, 0,
                       std::string("'") + key + " " + std::to_string(n) + "': more " + what +
                           " than the line holds");
    return std::pair(std::move(s), n);
  };
  auto names = [&](const char* key, std::vector<std::string>& out) {
    auto [s, n] = counted(key, 1, "names");
    out.resize(n);
    for (auto& x : out)
      if (!(s >> x))
        throw InputError(
            path, ln, 0,
            std::string("expected ") + std::to_string(n) + " names after '" + key + "'");
  };
  {
    auto [s, n] = counted("fitted_to", 2, "file digests");
    m.fitted_to.resize(n);
    for (auto& [file, digest] : m.fitted_to)
      if (!(s >> file >> digest))
        throw InputError(path, ln, 0,
                         "expected " + std::to_string(n) + " pairs of a file and its SHA-256");
    // Refused when the head's files are not the ones it was fitted to, naming the first.
    const auto now = head_file_digests(head);
    for (const auto& entry : now) {
      // References, not a structured binding: clang 14 cannot capture one in a lambda.
      const std::string& file = entry[0];
      const std::string& digest = entry[1];
      const auto it = std::find_if(m.fitted_to.begin(), m.fitted_to.end(),
                                   [&](const auto& r) { return r[0] == file; });
      if (it == m.fitted_to.end())
        throw InputError(path, ln, 0,
                         "stale: fitted without " + file + ", which the head now reads" + kRebuild);
      if ((*it)[1] != digest)
        throw InputError(
            path, ln, 0,
            "stale: " + head.dir + "/" + file + " changed since the model was fitted (SHA-256 " +
                (*it)[1].substr(0, 12) + "…, now " + digest.substr(0, 12) + "…)" + kRebuild);
    }
    if (m.fitted_to.size() != now.size())
      throw InputError(path, ln, 0,
                       "stale: fitted to files the head no longer reads" + std::string(kRebuild));
  }
  names("muscles", m.muscles);
  if (m.muscles != head.commanded)
    throw InputError(
        path, ln, 0,
        std::string("expected the muscles of head.yaml in order, found a different list") +
            kRebuild);
  names("control_points", m.control_points);
  if (m.control_points != head.control_points)
    throw InputError(path, ln, 0,
                     std::string("expected the control points of face.yaml in order, found a "
                                 "different list") +
                         kRebuild);
  {
    auto [s, n] = counted("features", 3, "factor triples");
    const int last = variable_count(m.muscles.size()) - 1;
    // Distinct ascending triples over the last + 1 variables: C(last + 3, 3).
    const std::size_t v = static_cast<std::size_t>(last) + 1;
    const std::size_t most = v * (v + 1) * (v + 2) / 6;
    if (n > most)
      throw InputError(path, ln, 0,
                       "'features " + std::to_string(n) + "': expected at most " +
                           std::to_string(most) + ", the distinct factor triples of " +
                           std::to_string(v) + " variables");
    m.features.resize(n);
    std::set<std::array<int, 3>> seen;
    for (auto& t : m.features)
      if (!(s >> t[0] >> t[1] >> t[2]) || t[0] < 0 || t[2] > last || t[0] > t[1] || t[1] > t[2] ||
          !seen.insert(t).second)
        throw InputError(path, ln, 0,
                         "expected " + std::to_string(n) +
                             " distinct ascending factor triples of variables 0.." +
                             std::to_string(last));
    // Two triples of one product (c·c·1 and 1·1·c², say) would be two equal columns, and a
    // degree above four is beyond what the fit writes and verify's rounding margin covers.
    std::map<std::vector<std::array<int, 2>>, std::size_t> product;
    const std::vector<Monomial> monomials = feature_monomials(m);
    for (std::size_t k = 0; k < monomials.size(); ++k) {
      int degree = 0;
      for (const auto& [var, power] : monomials[k].powers) degree += power;
      if (degree > 4)
        throw InputError(path, ln, 0,
                         "feature " + std::to_string(k) + " has degree " + std::to_string(degree) +
                             ": expected at most 4");
      const auto [at, added] = product.emplace(monomials[k].powers, k);
      if (!added)
        throw InputError(path, ln, 0,
                         "features " + std::to_string(at->second) + " and " + std::to_string(k) +
                             " are the same product of the variables");
    }
  }
  auto s = next("'coefficients ROWS COLS'");
  std::string tag;
  Eigen::Index rows = 0, cols = 0;
  if (!(s >> tag >> rows >> cols) || tag != "coefficients" ||
      rows != 3 * static_cast<Eigen::Index>(m.control_points.size()) ||
      cols != static_cast<Eigen::Index>(m.features.size()))
    throw InputError(path, ln, 0,
                     "expected 'coefficients " + std::to_string(3 * m.control_points.size()) + " " +
                         std::to_string(m.features.size()) + "', found '" + line + "'");
  m.coefficients.resize(rows, cols);
  for (Eigen::Index i = 0; i < rows; ++i) {
    auto r = next("a row of coefficients");
    for (Eigen::Index j = 0; j < cols; ++j)
      if (!(r >> m.coefficients(i, j)) || !std::isfinite(m.coefficients(i, j)))
        throw InputError(
            path, ln, 0,
            "expected " + std::to_string(cols) + " finite numbers, found fewer or a non-number");
  }
  return m;
}

}  // namespace facectl::face
