// Colour management through OpenColorIO: finds and loads the config ($OCIO, else the one
// shipped in ocio/), names the scene-linear Rec.709 working space, and converts CPU pixels
// from any of the config's colour spaces into it. The GPU display transform lives in
// display_transform.h and shares the loaded config through this class.
#pragma once

#include <aquarelle/core/image.h>
#include <aquarelle/core/result.h>

#include <memory>
#include <string>
#include <vector>

namespace aq {

// Opaque holder of the OCIO config (keeps OpenColorIO headers out of the public API).
struct ColorConfigData;

class ColorConfig {
 public:
  // $OCIO when set; otherwise the first of AQ_SOURCE_DIR/ocio/config.ocio,
  // AQ_INSTALL_DATADIR/ocio/config.ocio, <exe>/../share/aquarelle/ocio/config.ocio that exists.
  // The error names every file tried and OCIO's message.
  static Result<ColorConfig> load();
  // Loads one specific config file (tests, `--ocio` style overrides).
  static Result<ColorConfig> load_file(const std::string& path);

  // The file the config was read from.
  const std::string& path() const;
  // The config file and every LUT file it names (what writers must never overwrite).
  std::vector<std::string> files() const;
  // The scene-linear working space: the config's "scene_linear" role ("lin_rec709" in ours).
  std::string working_space() const;
  std::vector<std::string> colorspaces() const;
  bool has_colorspace(const std::string& name) const;

  // In-place CPU conversion of RGBA (or RGB) float pixels from `colorspace` to the working
  // space. Alpha is left untouched. An unknown colour space is an error listing the known ones.
  Status to_working(ImageF& image, const std::string& colorspace) const;
  // The inverse, for tests and for writing data in a named space.
  Status from_working(ImageF& image, const std::string& colorspace) const;

  std::vector<std::string> displays() const;
  // Views of `display` (the default display when empty).
  std::vector<std::string> views(const std::string& display = "") const;
  std::string default_display() const;
  std::string default_view() const;  // of the default display

  // For display_transform.cpp and image_io.cpp only.
  const std::shared_ptr<const ColorConfigData>& data() const { return data_; }

 private:
  explicit ColorConfig(std::shared_ptr<const ColorConfigData> data) : data_(std::move(data)) {}
  std::shared_ptr<const ColorConfigData> data_;
};

}  // namespace aq
