// Finding, loading and querying the OpenColorIO config, and CPU conversions into the working
// space. OCIO reports problems by throwing; every call into it is wrapped so callers get
// aq::Error values that name the config file and the colour space involved.
#include <aquarelle/core/color.h>

#include <aquarelle/sdk/regular_file.hpp>

#include "color_config_data.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>
#include <vector>

namespace aq {
namespace {

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) {
    if (!out.empty()) out += ", ";
    out += "\"" + item + "\"";
  }
  return out;
}

std::string executable_dir() {
  std::error_code ec;
  auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : exe.parent_path().string();
}

// Where the shipped config may be, in the order they are tried.
std::vector<std::string> shipped_config_candidates() {
  std::vector<std::string> candidates;
#ifdef AQ_SOURCE_DIR
  candidates.push_back(AQ_SOURCE_DIR "/ocio/config.ocio");
#endif
#ifdef AQ_INSTALL_DATADIR
  candidates.push_back(AQ_INSTALL_DATADIR "/ocio/config.ocio");
#endif
  if (auto dir = executable_dir(); !dir.empty()) {
    candidates.push_back(dir + "/../share/aquarelle/ocio/config.ocio");
  }
  return candidates;
}

Status convert(const ColorConfigData& data, ImageF& image, const std::string& from,
               const std::string& to) {
  if (image.empty()) return Ok{};
  if (image.channels != 3 && image.channels != 4) {
    return make_error("colour conversion from \"" + from + "\" to \"" + to + "\": image has " +
                      std::to_string(image.channels) +
                      " channels; only RGB and RGBA images can be converted");
  }
  for (const auto& name : {from, to}) {
    if (!data.config->getColorSpace(name.c_str())) {
      std::vector<std::string> known;
      for (int i = 0; i < data.config->getNumColorSpaces(); ++i) {
        known.emplace_back(data.config->getColorSpaceNameByIndex(i));
      }
      return make_error("unknown colour space \"" + name + "\" in OCIO config " + data.path +
                        "; known colour spaces: " + join(known) +
                        " (choose one of them, or point $OCIO at a config that has it)");
    }
  }
  try {
    auto processor = data.config->getProcessor(from.c_str(), to.c_str());
    if (processor->isNoOp()) return Ok{};
    auto cpu = processor->getDefaultCPUProcessor();
    OCIO::PackedImageDesc desc(image.pixels.data(), image.width, image.height, image.channels);
    cpu->apply(desc);
  } catch (const OCIO::Exception& e) {
    return make_error("OCIO could not convert from \"" + from + "\" to \"" + to +
                      "\" with config " + data.path + ": " + e.what());
  }
  return Ok{};
}

}  // namespace

Result<ColorConfig> ColorConfig::load() {
  if (const char* env = std::getenv("OCIO"); env && *env) {
    auto config = load_file(env);
    if (!config) {
      return make_error(config.message() +
                        " (the path came from $OCIO; fix it or unset $OCIO to use the config "
                        "shipped with Aquarelle)");
    }
    return config;
  }
  std::vector<std::string> tried = shipped_config_candidates();
  for (const auto& candidate : tried) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(candidate, ec)) return load_file(candidate);
  }
  std::string message = "no OpenColorIO config found: $OCIO is not set and none of";
  for (const auto& candidate : tried) message += " " + candidate;
  message += " exists; set $OCIO to a config file or reinstall Aquarelle (ocio/config.ocio)";
  return make_error(message);
}

namespace {

// Every FileTransform under `transform`, groups included.
void collect_file_transforms(const OCIO::ConstTransformRcPtr& transform,
                             std::vector<std::string>* sources) {
  if (!transform) return;
  if (auto file = OCIO::DynamicPtrCast<const OCIO::FileTransform>(transform)) {
    if (file->getSrc() != nullptr && *file->getSrc() != '\0') sources->emplace_back(file->getSrc());
  } else if (auto group = OCIO::DynamicPtrCast<const OCIO::GroupTransform>(transform)) {
    for (int i = 0; i < group->getNumTransforms(); ++i) {
      collect_file_transforms(group->getTransform(i), sources);
    }
  }
}

// Every LUT file the config names (colour spaces, looks, view transforms), resolved as OCIO
// resolves it; names OCIO cannot resolve are left out (OCIO reports them if ever needed).
std::vector<std::string> lut_files(const OCIO::Config& config) {
  std::vector<std::string> sources;
  for (int i = 0; i < config.getNumColorSpaces(); ++i) {
    auto space = config.getColorSpace(config.getColorSpaceNameByIndex(i));
    if (!space) continue;
    collect_file_transforms(space->getTransform(OCIO::COLORSPACE_DIR_TO_REFERENCE), &sources);
    collect_file_transforms(space->getTransform(OCIO::COLORSPACE_DIR_FROM_REFERENCE), &sources);
  }
  for (int i = 0; i < config.getNumLooks(); ++i) {
    auto look = config.getLook(config.getLookNameByIndex(i));
    if (!look) continue;
    collect_file_transforms(look->getTransform(), &sources);
    collect_file_transforms(look->getInverseTransform(), &sources);
  }
  for (int i = 0; i < config.getNumViewTransforms(); ++i) {
    auto view = config.getViewTransform(config.getViewTransformNameByIndex(i));
    if (!view) continue;
    collect_file_transforms(view->getTransform(OCIO::VIEWTRANSFORM_DIR_TO_REFERENCE), &sources);
    collect_file_transforms(view->getTransform(OCIO::VIEWTRANSFORM_DIR_FROM_REFERENCE), &sources);
  }
  auto context = config.getCurrentContext();
  std::vector<std::string> resolved;
  for (const std::string& source : sources) {
    try {
      resolved.emplace_back(context->resolveFileLocation(source.c_str()));
    } catch (const OCIO::Exception&) {
    }
  }
  return resolved;
}

// OCIO opens a config's LUT files only when a processor needs them, and would block on a FIFO
// or read /dev/zero without end as it would for the config itself: every file named by a
// colour space, look or view transform must resolve to a regular file before it is used.
Status check_lut_files(const OCIO::Config& config) {
  for (const std::string& resolved : lut_files(config)) {
    if (std::string why = files::regular_file_problem(resolved); !why.empty()) {
      return make_error("its LUT file " + resolved + ": " + why);
    }
  }
  return Ok{};
}

}  // namespace

Result<ColorConfig> ColorConfig::load_file(const std::string& path) {
  // Only a regular file: OCIO would block on a FIFO and read /dev/zero without end.
  if (std::string why = files::regular_file_problem(path); !why.empty()) {
    return make_error("cannot load OpenColorIO config " + path + ": " + why);
  }
  auto data = std::make_shared<ColorConfigData>();
  data->path = path;
  try {
    data->config = OCIO::Config::CreateFromFile(path.c_str());
    data->config->validate();
  } catch (const OCIO::Exception& e) {
    return make_error("cannot load OpenColorIO config " + path + ": " + e.what());
  }
  if (auto luts = check_lut_files(*data->config); !luts) {
    return make_error("cannot load OpenColorIO config " + path + ": " + luts.message());
  }
  auto linear = data->config->getColorSpace(OCIO::ROLE_SCENE_LINEAR);
  if (!linear) {
    return make_error("OpenColorIO config " + path +
                      " has no \"scene_linear\" role; add `scene_linear: <linear Rec.709 space>` "
                      "under `roles:`");
  }
  data->working_space = linear->getName();
  return ColorConfig(std::move(data));
}

const std::string& ColorConfig::path() const {
  return data_->path;
}

std::vector<std::string> ColorConfig::files() const {
  std::vector<std::string> files = lut_files(*data_->config);
  files.insert(files.begin(), data_->path);
  return files;
}

std::string ColorConfig::working_space() const {
  return data_->working_space;
}

std::vector<std::string> ColorConfig::colorspaces() const {
  std::vector<std::string> names;
  for (int i = 0; i < data_->config->getNumColorSpaces(); ++i) {
    names.emplace_back(data_->config->getColorSpaceNameByIndex(i));
  }
  return names;
}

bool ColorConfig::has_colorspace(const std::string& name) const {
  return !name.empty() && data_->config->getColorSpace(name.c_str()) != nullptr;
}

Status ColorConfig::to_working(ImageF& image, const std::string& colorspace) const {
  return convert(*data_, image, colorspace, data_->working_space);
}

Status ColorConfig::from_working(ImageF& image, const std::string& colorspace) const {
  return convert(*data_, image, data_->working_space, colorspace);
}

std::vector<std::string> ColorConfig::displays() const {
  std::vector<std::string> names;
  for (int i = 0; i < data_->config->getNumDisplays(); ++i) {
    names.emplace_back(data_->config->getDisplay(i));
  }
  return names;
}

std::vector<std::string> ColorConfig::views(const std::string& display) const {
  const std::string name = display.empty() ? default_display() : display;
  std::vector<std::string> names;
  for (int i = 0; i < data_->config->getNumViews(name.c_str()); ++i) {
    names.emplace_back(data_->config->getView(name.c_str(), i));
  }
  return names;
}

std::string ColorConfig::default_display() const {
  return data_->config->getDefaultDisplay();
}

std::string ColorConfig::default_view() const {
  const std::string display = default_display();
  return data_->config->getDefaultView(display.c_str());
}

}  // namespace aq
