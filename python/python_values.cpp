// Bounded conversion of Python values to parameter JSON (see python_values.h).
#include "python_values.h"

#include <climits>

#include "python_graph.h"

namespace py = pybind11;

namespace aq::python {

namespace {

class Converter {
 public:
  explicit Converter(std::string where) : where_(std::move(where)) {}

  nlohmann::json convert(const py::handle& value, int depth) {
    if (depth > kMaxValueDepth) {
      fail("nests lists more than " + std::to_string(kMaxValueDepth) +
           " deep (a list that contains itself?)");
    }
    count(1);
    if (value.is_none()) return nullptr;
    if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
    if (py::isinstance<py::int_>(value)) return integer(value);
    if (py::isinstance<py::float_>(value)) return value.cast<double>();
    if (py::isinstance<py::str>(value)) return text(value);
    if (py::isinstance<py::dict>(value)) {
      check_length(value);
      nlohmann::json object = nlohmann::json::object();
      for (auto item : value.cast<py::dict>()) {
        object[text(py::str(item.first))] = convert(item.second, depth + 1);
      }
      return object;
    }
    if (py::hasattr(value, "__iter__")) {  // list, tuple, NumPy array, iterators
      check_length(value);
      nlohmann::json array = nlohmann::json::array();
      for (auto item : value) array.push_back(convert(item, depth + 1));
      return array;
    }
    if (py::hasattr(value, "__float__")) return value.cast<double>();  // NumPy scalars
    fail("cannot be a Python " + std::string(py::str(value.get_type().attr("__name__"))) +
         ": give a number, bool, string or list");
  }

 private:
  [[noreturn]] void fail(const std::string& why) const { throw Failure(where_ + ": " + why); }

  // Every element counts; Ctrl-C is honoured while an endless iterator is drained (the C++
  // loop runs no bytecode, so Python would only see the signal at the end).
  void count(size_t elements) {
    elements_ += elements;
    if (elements_ > kMaxValueElements) {
      fail("holds more than " + std::to_string(kMaxValueElements) +
           " values (an endless iterator or a large array?); parameters hold a few numbers");
    }
    if ((elements_ & 255) == 0 && PyErr_CheckSignals() != 0) throw py::error_already_set();
  }

  // Sized containers are refused before they are walked.
  void check_length(const py::handle& value) {
    if (!py::hasattr(value, "__len__")) return;
    const Py_ssize_t length = PyObject_Length(value.ptr());
    if (length < 0) {
      PyErr_Clear();
      return;
    }
    if (static_cast<size_t>(length) > kMaxValueElements - elements_) count(length);
  }

  nlohmann::json integer(const py::handle& value) {
    int overflow = 0;
    const long long number = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
    if (overflow != 0 || (number == -1 && PyErr_Occurred() != nullptr)) {
      PyErr_Clear();
      fail("the integer " + abbreviated(std::string(py::str(value))) +
           " is out of range (at most 64 bits)");
    }
    return static_cast<int64_t>(number);
  }

  std::string text(const py::handle& value) {
    Py_ssize_t size = 0;
    const char* data = PyUnicode_AsUTF8AndSize(value.ptr(), &size);
    if (data == nullptr) {
      PyErr_Clear();
      fail("the string is not valid Unicode text");
    }
    strings_ += static_cast<size_t>(size);
    if (strings_ > kMaxValueStringBytes) {
      fail("holds more than " + std::to_string(kMaxValueStringBytes) + " bytes of text");
    }
    return std::string(data, static_cast<size_t>(size));
  }

  static std::string abbreviated(const std::string& digits) {
    return digits.size() <= 24 ? digits
                               : digits.substr(0, 10) + "..." + digits.substr(digits.size() - 4) +
                                     " (" + std::to_string(digits.size()) + " digits)";
  }

  std::string where_;
  size_t elements_ = 0;
  size_t strings_ = 0;
};

}  // namespace

nlohmann::json parameter_value_from_python(const py::handle& value, const std::string& where) {
  return Converter(where).convert(value, 0);
}

}  // namespace aq::python
