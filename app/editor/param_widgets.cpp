// Parameter widgets. See param_widgets.h.
#include "param_widgets.h"

#include <aquarelle/core/graph_io.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cfloat>
#include <climits>
#include <cmath>

namespace aq::editor {

namespace {

// ImGui 1.86's SliderBehavior asserts these bounds (IM_S32_MIN / 2, IM_S32_MAX / 2,
// ±FLT_MAX / 2): a range beyond them must not reach a slider.
constexpr double kSliderIntMin = INT_MIN / 2;
constexpr double kSliderIntMax = INT_MAX / 2;
constexpr double kSliderFloatLimit = FLT_MAX / 2.0;

double clamp_finite(double v, double lo, double hi) {
  if (std::isnan(v)) return 0.0;
  return std::clamp(v, lo, hi);
}

NumberWidget widget_for(const ParamInfo& param, double slider_min, double slider_max,
                        double type_min, double type_max) {
  NumberWidget widget;
  const double lo = param.min_value;
  const double hi = param.max_value;
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(hi > lo)) return widget;  // unclamped drag
  widget.min = clamp_finite(lo, type_min, type_max);
  widget.max = clamp_finite(hi, type_min, type_max);
  widget.slider = lo >= slider_min && hi <= slider_max && widget.max > widget.min;
  return widget;
}

double number_or_default(const nlohmann::json& value, const ParamInfo& param, int index) {
  if (value.is_number()) return value.get<double>();
  if (value.is_boolean()) return value.get<bool>() ? 1.0 : 0.0;
  return param.default_value[index];
}

const char* kFloatFormat = "%.4g";

std::optional<ParamEdit> draw_float(const ParamInfo& param, const nlohmann::json& value) {
  float v = float_value_of(value, param);
  const NumberWidget widget = float_widget_for(param);
  const float lo = static_cast<float>(widget.min);
  const float hi = static_cast<float>(widget.max);
  bool changed = false;
  if (widget.slider) {
    ImGuiSliderFlags flags = param.ui_hint == "log" ? ImGuiSliderFlags_Logarithmic : 0;
    changed = ImGui::SliderFloat(param.name.c_str(), &v, lo, hi, kFloatFormat, flags);
  } else {
    const float speed = param.step > 0 ? static_cast<float>(param.step) : 0.01f;
    changed = ImGui::DragFloat(param.name.c_str(), &v, speed, lo, hi, kFloatFormat,
                               hi > lo ? ImGuiSliderFlags_AlwaysClamp : 0);
  }
  if (!changed || !std::isfinite(v)) return std::nullopt;
  return ParamEdit{static_cast<double>(v), true};
}

std::optional<ParamEdit> draw_int(const ParamInfo& param, const nlohmann::json& value) {
  int v = int_value_of(value, param);
  const NumberWidget widget = int_widget_for(param);
  const int lo = static_cast<int>(widget.min);
  const int hi = static_cast<int>(widget.max);
  bool changed = false;
  if (widget.slider) {
    changed = ImGui::SliderInt(param.name.c_str(), &v, lo, hi);
  } else {
    const float speed = param.step >= 1 ? static_cast<float>(param.step) : 1.0f;
    changed = ImGui::DragInt(param.name.c_str(), &v, speed, lo, hi, "%d",
                             hi > lo ? ImGuiSliderFlags_AlwaysClamp : 0);
  }
  if (!changed) return std::nullopt;
  return ParamEdit{v, true};
}

std::optional<ParamEdit> draw_enum(const ParamInfo& param, const nlohmann::json& value) {
  const std::string current = enum_value_of(value, param);
  std::optional<ParamEdit> edit;
  if (ImGui::BeginCombo(param.name.c_str(), current.c_str())) {
    for (const auto& name : param.enum_values) {
      if (ImGui::Selectable(name.c_str(), name == current) && name != current) {
        edit = ParamEdit{name, false};
      }
    }
    ImGui::EndCombo();
  }
  return edit;
}

std::optional<ParamEdit> draw_vec3(const ParamInfo& param, const nlohmann::json& value) {
  std::array<float, 3> v = vec3_value_of(value, param);
  bool changed = false;
  if (param.type == AQ_PARAM_COLOR) {
    changed = ImGui::ColorEdit3(param.name.c_str(), v.data(),
                                ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR);
  } else {
    const NumberWidget widget = float_widget_for(param);
    const float speed = param.step > 0 ? static_cast<float>(param.step) : 0.01f;
    changed = ImGui::DragFloat3(param.name.c_str(), v.data(), speed, static_cast<float>(widget.min),
                                static_cast<float>(widget.max), kFloatFormat);
  }
  if (!changed) return std::nullopt;
  for (float c : v) {
    if (!std::isfinite(c)) return std::nullopt;
  }
  return ParamEdit{nlohmann::json::array({v[0], v[1], v[2]}), true};
}

}  // namespace

NumberWidget int_widget_for(const ParamInfo& param) {
  return widget_for(param, kSliderIntMin, kSliderIntMax, INT_MIN, INT_MAX);
}

NumberWidget float_widget_for(const ParamInfo& param) {
  return widget_for(param, -kSliderFloatLimit, kSliderFloatLimit, -FLT_MAX, FLT_MAX);
}

int int_value_of(const nlohmann::json& value, const ParamInfo& param) {
  return static_cast<int>(
      std::llround(clamp_finite(number_or_default(value, param, 0), INT_MIN, INT_MAX)));
}

float float_value_of(const nlohmann::json& value, const ParamInfo& param) {
  return static_cast<float>(clamp_finite(number_or_default(value, param, 0), -FLT_MAX, FLT_MAX));
}

std::array<float, 3> vec3_value_of(const nlohmann::json& value, const ParamInfo& param) {
  std::array<float, 3> v{};
  const bool stored = value.is_array() && value.size() == 3;
  for (int i = 0; i < 3; ++i) {
    const double c =
        stored && value[i].is_number() ? value[i].get<double>() : param.default_value[i];
    v[i] = static_cast<float>(clamp_finite(c, -FLT_MAX, FLT_MAX));
  }
  return v;
}

std::string enum_value_of(const nlohmann::json& value, const ParamInfo& param) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_number_integer() && value.get<long long>() >= 0 &&
      value.get<long long>() < static_cast<long long>(param.enum_values.size())) {
    return param.enum_values[value.get<size_t>()];
  }
  return "";
}

bool slider_int_guarded(const char* label, int* v, int lo, int hi, const char* format) {
  if (lo >= kSliderIntMin && hi <= kSliderIntMax && hi > lo) {
    return ImGui::SliderInt(label, v, lo, hi, format);
  }
  return ImGui::DragInt(label, v, 1.0f, lo, hi, format,
                        hi > lo ? ImGuiSliderFlags_AlwaysClamp : ImGuiSliderFlags_None);
}

std::optional<ParamEdit> draw_param_widget(const ParamInfo& param, const nlohmann::json& value) {
  switch (param.type) {
    case AQ_PARAM_FLOAT:
      return draw_float(param, value);
    case AQ_PARAM_INT:
      return draw_int(param, value);
    case AQ_PARAM_BOOL: {
      bool v = number_or_default(value, param, 0) != 0.0;
      if (ImGui::Checkbox(param.name.c_str(), &v)) return ParamEdit{v, false};
      return std::nullopt;
    }
    case AQ_PARAM_ENUM:
      return draw_enum(param, value);
    case AQ_PARAM_STRING:
    case AQ_PARAM_PATH: {
      std::string text = value.is_string() ? value.get<std::string>() : "";
      if (ImGui::InputText(param.name.c_str(), &text)) return ParamEdit{text, true};
      return std::nullopt;
    }
    case AQ_PARAM_COLOR:
    case AQ_PARAM_VEC3:
      return draw_vec3(param, value);
  }
  // A kind this editor does not know (a newer plugin ABI): shown, never edited.
  ImGui::TextDisabled("%s: %s", param.name.c_str(), value.dump().c_str());
  return std::nullopt;
}

}  // namespace aq::editor
