// One widget per parameter kind, chosen so that no declared range or stored value can trip
// Dear ImGui's own assertions (which abort the editor): its sliders hold integers only within
// ±2^30 and floats only within ±FLT_MAX/2, so a wider range (a `seed` declared over
// [0, 2147483647]) is edited with a drag field clamped to the range instead. Values read from
// the graph are converted without throwing, whatever the file holds.
#pragma once

#include <aquarelle/core/registry.h>

#include <nlohmann/json.hpp>

#include <array>
#include <optional>

namespace aq::editor {

// How a number with a declared range is edited: a slider, or a drag field clamped to
// [min, max] (min == max: not clamped).
struct NumberWidget {
  bool slider = false;
  double min = 0;
  double max = 0;
};

// The widget for an integer / float parameter: a slider only where ImGui's slider can hold the
// declared range (and the range is not empty).
NumberWidget int_widget_for(const ParamInfo& param);
NumberWidget float_widget_for(const ParamInfo& param);

// A stored value as the widget's type, never throwing: numbers clamped into the type, anything
// else (a string, null, a wrong-sized array) the parameter's default.
int int_value_of(const nlohmann::json& value, const ParamInfo& param);
float float_value_of(const nlohmann::json& value, const ParamInfo& param);
std::array<float, 3> vec3_value_of(const nlohmann::json& value, const ParamInfo& param);
// The enum's current name ("" when the value names none of its values).
std::string enum_value_of(const nlohmann::json& value, const ParamInfo& param);

// ImGui::SliderInt where its slider can hold [lo, hi], else a drag field clamped to it: the
// guard for every integer slider of the editor (the time bar's frames too).
bool slider_int_guarded(const char* label, int* v, int lo, int hi, const char* format = "%d");

// What the user did to a parameter's widget this frame.
struct ParamEdit {
  nlohmann::json value;
  bool continuous = false;  // part of a drag: merged into one undo step
};

// Draws `param`'s widget (needs an ImGui frame) with `value` from the graph; returns the new
// value when the user changed it. Every parameter kind goes through here.
std::optional<ParamEdit> draw_param_widget(const ParamInfo& param, const nlohmann::json& value);

}  // namespace aq::editor
