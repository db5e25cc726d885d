#pragma once
// The registry of element types with states of their own (model/element.hpp), read by the
// compiler of `drives:` (model/compile_drive.cpp). Each type registers itself in its own file
// src/elements/types/NAME.cpp with
//
//   MACHDYN_ELEMENT_TYPE(NAME, "yaml-type", compile_function)
//
// at file scope, where NAME is the file's name. CMake (cmake/ElementTypes.cmake) lists those files
// and generates the one table that refers to each registration (generated/element_types_table.cpp in
// the build tree), so the static library keeps every type's object file and adding a type edits no
// other file; a file without its registration is a link error naming it.
#include <memory>
#include <string>
#include <vector>

#include "machdyn/common/spec.hpp"
#include "machdyn/model/element.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn::detail {

/// One element type: its `type:` and its compile function, which reads the fields of one entry
/// (`type` and `body` already read; its body is of `body_kind`) into the element in SI, reporting
/// every problem located through `f` (f.finish() is called after it). Null when a field was bad.
struct ElementType {
  const char* name;
  std::shared_ptr<const Element> (*compile)(FieldReader& f, BodyKind body_kind);
};

/// Every registered type, in the order of their files' names.
const std::vector<const ElementType*>& element_types();
/// The type named `name`, or null.
const ElementType* find_element_type(std::string_view name);

}  // namespace machdyn::detail

/// Registers an element type from its own file src/elements/types/NAME.cpp (NAME: the file's name).
#define MACHDYN_ELEMENT_TYPE(NAME, TYPE, COMPILE)                                \
  const ::machdyn::detail::ElementType& machdyn_element_type_##NAME() {          \
    static const ::machdyn::detail::ElementType kType{TYPE, &(COMPILE)};         \
    return kType;                                                                \
  }
