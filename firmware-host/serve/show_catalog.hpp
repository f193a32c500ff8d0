#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/inputs/show.hpp"

namespace facectl {

// The shows `facectl serve` may play: the *.yaml files of one folder, by file
// name without the extension. A name is only a name (letters, digits, '-',
// '_', '.'; no '/' and no leading '.'), so no request can reach another file.
// Each show is loaded and validated against the head when asked for, so an
// edited file plays as edited; a file that fails to load gives its error.
class ShowCatalog {
 public:
  struct Listing {
    std::string name;
    double duration_s = 0.0;
    std::string error;  // why it does not load, or empty
  };

  ShowCatalog(std::string folder, const LoadedConfig& config);

  const std::string& folder() const { return folder_; }
  std::vector<Listing> list() const;
  // Throws std::out_of_range for an unknown or ill-formed name, ConfigError
  // when the file fails to load.
  std::shared_ptr<const Show> load(const std::string& name) const;

  static bool valid_name(const std::string& name);

 private:
  std::string folder_;
  const LoadedConfig& config_;
};

// The folder of the runtime file's `serve.shows`, else that of its `show:`,
// else the `shows` folder beside the runtime file.
std::string shows_folder(const LoadedConfig& config);

}  // namespace facectl
