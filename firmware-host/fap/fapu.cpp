#include "firmware-host/fap/fapu.hpp"

#include "facectl/face/obj_io.hpp"
#include "firmware-host/config/config_node.hpp"

namespace facectl {

FeaturePoints FeaturePoints::load(const face::HeadSpec& spec) {
  const face::TriMesh skin = face::read_obj(spec.skin_file, spec.skin_scale);
  FeaturePoints fp;
  fp.source_ = spec.dir + "/landmarks.yaml";
  for (const auto& l : spec.landmarks) {
    face::Vec3 s = face::Vec3::Zero();
    for (int v : l.vertices) {
      if (v < 0 || static_cast<std::size_t>(v) >= skin.v.size()) {
        throw ConfigError(fp.source_ + ": landmark " + l.name + ": expected a vertex of " +
                          spec.skin_file + ", found index " + std::to_string(v));
      }
      s += skin.v.get(v);
    }
    fp.points_[l.name] = s / static_cast<double>(l.vertices.size()) + l.offset;
  }
  return fp;
}

const face::Vec3& FeaturePoints::at(const std::string& name) const {
  const auto it = points_.find(name);
  if (it == points_.end()) {
    throw ConfigError(source_ + ": expected landmark '" + name +
                      "' (an MPEG-4 feature point the FAP input needs), found none");
  }
  return it->second;
}

double Fapu::unit(FapUnit u) const {
  switch (u) {
    case FapUnit::kMNS:
      return mns0 / 1024.0;
    case FapUnit::kMW:
      return mw0 / 1024.0;
    case FapUnit::kENS:
      return ens0 / 1024.0;
    case FapUnit::kES:
      return es0 / 1024.0;
    case FapUnit::kIRISD:
      return irisd0 / 1024.0;
    case FapUnit::kAU:
      return kAu;
    case FapUnit::kNone:
      break;
  }
  return 0.0;
}

Fapu compute_fapu(const FeaturePoints& fp) {
  const face::Vec3 nose_base = 0.5 * (fp.at("fdp_9_1") + fp.at("fdp_9_2"));
  const double pupils_y = 0.5 * (fp.at("fdp_3_5").y() + fp.at("fdp_3_6").y());
  Fapu f;
  f.es0 = fp.at("fdp_3_5").x() - fp.at("fdp_3_6").x();
  f.ens0 = pupils_y - nose_base.y();
  f.mns0 = nose_base.y() - fp.at("fdp_2_2").y();
  f.mw0 = fp.at("fdp_8_3").x() - fp.at("fdp_8_4").x();
  f.irisd0 = 0.5 * ((fp.at("fdp_3_1").y() - fp.at("fdp_3_3").y()) +
                    (fp.at("fdp_3_2").y() - fp.at("fdp_3_4").y()));
  const std::pair<const char*, double> all[] = {
      {"ES0", f.es0}, {"ENS0", f.ens0}, {"MNS0", f.mns0}, {"MW0", f.mw0}, {"IRISD0", f.irisd0}};
  for (const auto& [name, value] : all) {
    if (!(value > 0.0)) {
      throw ConfigError(std::string("FAPU ") + name +
                        ": expected a positive distance between the head's feature points, "
                        "found " +
                        std::to_string(value * 1e3) + " mm");
    }
  }
  return f;
}

}  // namespace facectl
