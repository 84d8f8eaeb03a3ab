// Python values as parameter values (JSON), within bounds: Graph.set once recursed without
// end on a self-referencing list (SIGSEGV), grew 1.4 GB from an 80 MB NumPy array, ate memory
// from an endless iterator while ignoring Ctrl-C, and answered 2**70 with pybind11's "Unable
// to cast" naming nothing. Every refusal names the parameter ("node 'blur', parameter
// 'sigma'") and says what fits.
#pragma once

#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

#include <string>

namespace aq::python {

// No parameter needs more: the largest are colours and vectors of 3 numbers; lists inside
// lists are kept for future parameters but bounded.
inline constexpr int kMaxValueDepth = 16;
inline constexpr size_t kMaxValueElements = 1u << 16;
inline constexpr size_t kMaxValueStringBytes = 1u << 20;

// `where` names the parameter for messages. Throws Failure when the value does not fit, and
// pybind11::error_already_set (KeyboardInterrupt) when SIGINT arrives while converting.
nlohmann::json parameter_value_from_python(const pybind11::handle& value, const std::string& where);

}  // namespace aq::python
