#include "firmware-host/verify/verify_command.hpp"

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/verify/adversarial_search.hpp"
#include "firmware-host/verify/show_check.hpp"
#include "firmware-host/verify/static_proof.hpp"

namespace facectl {
namespace {

using verify::Finding;
using Json = nlohmann::ordered_json;

Json to_json(const Finding& f) {
  return {{"severity", verify::to_string(f.severity)},
          {"check", f.check},
          {"subject", f.subject},
          {"message", f.message},
          {"witness", f.witness}};
}

void print_findings(const std::vector<Finding>& findings, bool include_info) {
  for (const Finding& f : findings) {
    if (!include_info && f.severity == Finding::Severity::kInfo) continue;
    std::printf("  %-4s %s%s%s: %s\n", verify::to_string(f.severity), f.check.c_str(),
                f.subject.empty() ? "" : " ", f.subject.c_str(), f.message.c_str());
    if (!f.witness.empty()) std::printf("       witness: %s\n", f.witness.c_str());
  }
}

}  // namespace

int verify_command(const VerifyOptions& o) {
  LoadedConfig cfg;
  try {
    ConfigOverrides overrides;
    overrides.rig_path = o.rig;
    overrides.keep_problems = true;
    cfg = load_config(o.config.empty() ? default_config_path() : o.config, overrides);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "facectl verify: %s\n", e.what());
    return 2;
  }
  Json report;
  report["rig"] = o.rig;
  report["head"] = cfg.head.name;
  bool failed = false;
  try {
    std::printf("facectl verify %s (head %s, %zu actuators)\n", o.rig.c_str(),
                cfg.head.name.c_str(), cfg.built.model.actuators.size());
    for (const std::string& w : cfg.built.warnings) std::printf("  %s\n", w.c_str());

    // a. Static proof.
    const verify::StaticProof proof = verify::prove(cfg);
    std::printf("\nStatic proof over the admissible face set (%.3f s)\n", proof.seconds);
    std::printf("  %-22s %10s %10s  %-16s %-16s %9s  %s\n", "actuator", "min", "max", "hardware",
                "soft", "margin", "method");
    Json actuators = Json::array();
    for (const auto& a : proof.actuators) {
      char hw[40], soft[40];
      std::snprintf(hw, sizeof hw, "[%.4g, %.4g]", a.hardware_min, a.hardware_max);
      std::snprintf(soft, sizeof soft, "[%.4g, %.4g]", a.soft_min, a.soft_max);
      std::printf("  %-22s %10.4g %10.4g  %-16s %-16s %9.4g  %s %s\n", a.name.c_str(), a.lo, a.hi,
                  hw, soft, a.hardware_margin, a.unit.c_str(), a.method.c_str());
      actuators.push_back({{"name", a.name},
                           {"unit", a.unit},
                           {"min", a.lo},
                           {"max", a.hi},
                           {"hardware_min", a.hardware_min},
                           {"hardware_max", a.hardware_max},
                           {"soft_min", a.soft_min},
                           {"soft_max", a.soft_max},
                           {"hardware_margin", a.hardware_margin},
                           {"soft_margin", a.soft_margin},
                           {"method", a.method},
                           {"proven", a.proven}});
    }
    print_findings(proof.findings, true);
    failed = failed || verify::any_failure(proof.findings);
    Json sf = Json::array();
    for (const auto& f : proof.findings) sf.push_back(to_json(f));
    report["static"] = {{"seconds", proof.seconds}, {"actuators", actuators}, {"findings", sf}};

    // b. Adversarial search.
    const verify::SearchResult search = verify::adversarial_search(cfg, {o.ticks, o.seed});
    std::printf("\nAdversarial search: %llu ticks, seed %llu (%.2f s): %llu violation(s)\n",
                static_cast<unsigned long long>(search.ticks),
                static_cast<unsigned long long>(o.seed), search.seconds,
                static_cast<unsigned long long>(search.violations));
    std::printf("  %-22s %12s %10s %9s %9s %9s\n", "actuator", "hw margin", "soft", "vel", "acc",
                "jerk");
    Json margins = Json::array();
    for (const auto& a : search.actuators) {
      std::printf("  %-22s %12.4g %10.4g %8.1f%% %8.1f%% %8.1f%%\n", a.name.c_str(), a.hardware,
                  a.soft, 100 * a.velocity, 100 * a.acceleration, 100 * a.jerk);
      margins.push_back({{"name", a.name},
                         {"hardware_margin", a.hardware},
                         {"soft_margin", a.soft},
                         {"velocity_margin_fraction", a.velocity},
                         {"acceleration_margin_fraction", a.acceleration},
                         {"jerk_margin_fraction", a.jerk}});
    }
    std::printf(
        "  face coupled limits: worst margin %.4g; actuator coupled limits: %.4g; "
        "mandible envelope: %.4g (SI)\n",
        search.face_constraint_margin, search.actuator_constraint_margin, search.envelope_margin);
    if (search.mechanism_envelope_margin < 1e300) {
      std::printf("  mandible envelope at the pose of the strut commands: worst margin %.4g (SI)\n",
                  search.mechanism_envelope_margin);
    }
    print_findings(search.findings, true);
    failed = failed || search.violations > 0;
    Json af = Json::array();
    for (const auto& f : search.findings) af.push_back(to_json(f));
    report["adversarial"] = {
        {"ticks", search.ticks},
        {"seed", o.seed},
        {"seconds", search.seconds},
        {"violations", search.violations},
        {"face_constraint_margin", search.face_constraint_margin},
        {"actuator_constraint_margin", search.actuator_constraint_margin},
        {"envelope_margin", search.envelope_margin},
        {"mechanism_envelope_margin", search.mechanism_envelope_margin < 1e300
                                          ? Json(search.mechanism_envelope_margin)
                                          : Json(nullptr)},
        {"actuators", margins},
        {"findings", af}};

    // c. Show check.
    Json shows = Json::array();
    for (std::size_t k = 0; k < o.shows.size(); ++k) {
      const std::string dir =
          o.plots.empty() ? "" : o.plots + (o.shows.size() > 1 ? "/show" + std::to_string(k) : "");
      const verify::ShowCheck sc = verify::check_show(cfg, o.shows[k], dir);
      std::printf("\nShow check %s (%.2f s): %s\n", sc.show.c_str(), sc.duration_s,
                  sc.fault      ? "THE HEAD FAULTED: fix the show or the rig"
                  : !sc.clean() ? "NEEDS CLAMPING: fix the show"
                                : "no clamp, no projection");
      if (sc.fault) {
        std::printf(
            "  FAIL %s at %.3f s: %s; %llu tick(s) outside IDLE, ENABLING, RUNNING and "
            "STOPPING\n",
            sc.fault->state.c_str(), sc.fault->at_s, sc.fault->reason.c_str(),
            static_cast<unsigned long long>(sc.fault->ticks));
      }
      Json list = Json::array();
      for (const auto& e : sc.engagements) {
        std::printf("  %8.3f..%8.3f s  %-22s %-20s size %.4g %s\n", e.start_s, e.end_s,
                    e.kind.c_str(), e.subject.c_str(), e.size, e.unit.c_str());
        list.push_back({{"kind", e.kind},
                        {"subject", e.subject},
                        {"start_s", e.start_s},
                        {"end_s", e.end_s},
                        {"size", e.size},
                        {"unit", e.unit}});
      }
      if (!sc.telemetry_csv.empty()) {
        std::printf("  telemetry %s, %d plot(s) in %s\n", sc.telemetry_csv.c_str(), sc.plots,
                    dir.c_str());
      }
      failed = failed || !sc.passed();
      Json show = {{"show", sc.show},
                   {"duration_s", sc.duration_s},
                   {"clean", sc.clean()},
                   {"passed", sc.passed()},
                   {"engagements", list}};
      if (sc.fault) {
        show["fault"] = {{"state", sc.fault->state},
                         {"at_s", sc.fault->at_s},
                         {"reason", sc.fault->reason},
                         {"ticks", sc.fault->ticks}};
      }
      shows.push_back(show);
    }
    report["shows"] = shows;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "facectl verify: %s\n", e.what());
    return 2;
  }
  report["result"] = failed ? "fail" : "pass";
  if (!o.json.empty()) {
    std::ofstream out(o.json);
    out << report.dump(2) << "\n";
    if (!out) {
      std::fprintf(stderr, "facectl verify: cannot write %s\n", o.json.c_str());
      return 2;
    }
  }
  std::printf("\nfacectl verify: %s\n", failed ? "FAIL" : "PASS");
  return failed ? 1 : 0;
}

}  // namespace facectl
