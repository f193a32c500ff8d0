#include "firmware-host/serve/show_catalog.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace facectl {

namespace fs = std::filesystem;

std::string shows_folder(const LoadedConfig& config) {
  const RuntimeConfig& rt = config.runtime;
  if (!rt.serve.shows_dir.empty()) return rt.serve.shows_dir;
  if (!rt.show_path.empty()) return fs::path(rt.show_path).parent_path().string();
  return resolve_path(rt.file, "shows");
}

ShowCatalog::ShowCatalog(std::string folder, const LoadedConfig& config)
    : folder_(std::move(folder)), config_(config) {}

bool ShowCatalog::valid_name(const std::string& name) {
  if (name.empty() || name.size() > 128 || name.front() == '.') return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
           c == '_' || c == '.';
  });
}

std::vector<ShowCatalog::Listing> ShowCatalog::list() const {
  std::vector<Listing> out;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder_, ec)) {
    if (!entry.is_regular_file(ec) || entry.path().extension() != ".yaml") continue;
    Listing l;
    l.name = entry.path().stem().string();
    if (!valid_name(l.name)) continue;
    try {
      l.duration_s = load(l.name)->duration();
    } catch (const std::exception& e) {
      l.error = e.what();
    }
    out.push_back(std::move(l));
  }
  std::sort(out.begin(), out.end(),
            [](const Listing& a, const Listing& b) { return a.name < b.name; });
  return out;
}

std::shared_ptr<const Show> ShowCatalog::load(const std::string& name) const {
  if (!valid_name(name)) throw std::out_of_range("'" + name + "' is not a show name");
  const fs::path path = fs::path(folder_) / (name + ".yaml");
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    throw std::out_of_range("no show '" + name + "' in " + folder_);
  }
  const ControllerModel& model = config_.built.model;
  return std::make_shared<const Show>(
      Show::load(path.string(), model.layout, model.neutral, config_.expressions));
}

}  // namespace facectl
