#pragma once
// numpy arrays over memory the library owns, without a copy: the array's base
// is a capsule holding a shared_ptr to the owner, so the memory lives as long
// as any array or view of it. The arrays are read-only, because the owner
// (a rendered image) is shared by every array made from it.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <utility>
#include <vector>

namespace obscura::python {

namespace py = pybind11;

template <typename T, typename Owner>
py::array_t<T> read_only_view(const T* data, std::vector<py::ssize_t> shape,
                              std::shared_ptr<const Owner> owner) {
  auto* keep = new std::shared_ptr<const Owner>(std::move(owner));
  py::capsule base(keep, [](void* p) { delete static_cast<std::shared_ptr<const Owner>*>(p); });
  py::array_t<T> array(shape, data, base);
  array.attr("setflags")(py::arg("write") = false);
  return array;
}

}  // namespace obscura::python
