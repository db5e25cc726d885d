#pragma once
// The registry of element types behind the one interface (model/element.hpp), read by the
// compilers of `drives:` and `links:` (model/compile_drive.cpp). Each type registers itself in its
// own file src/elements/types/NAME.cpp with
//
//   MACHDYN_ELEMENT_TYPE(NAME, "yaml-type", compile_function, "example fields")       (drives:, one body)
//   MACHDYN_LINK_ELEMENT_TYPE(NAME, "yaml-type", compile_function, "example fields")  (links:, two bodies)
//   MACHDYN_PLACED_ELEMENT_TYPE(NAME, "yaml-type", place_function, "example fields", "example bodies")
//                                                       (links:, the bodies named by its own fields)
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

/// One element type: its `type:`, its compile function, which reads the fields of one entry
/// (`type` and its bodies already read; its first body is of `body_kind`) into the element in SI,
/// reporting every problem located through `f` (f.finish() is called after it; null when a field was
/// bad), and the section it is written in with the number of its bodies: `drives:` with `body: B`
/// (one body) or `links:` with `between: [A, B]` (two bodies).
struct ElementType {
  const char* name;
  std::shared_ptr<const Element> (*compile)(FieldReader& f, BodyKind body_kind);
  const char* section = "drives";
  int bodies = 1;
  /// The fields of a small instance (a YAML flow map's body, without `type` and the bodies), for the
  /// conformance test over every registered type (tests/model/element_conformance_test.cpp): on a
  /// rotational body (or two) with inertia 1 kg·m², or on the bodies `example_bodies` gives.
  const char* example = "";
  /// A type whose own fields name its bodies (bodies = 0: a spatial rope's load and suspension
  /// bodies): `place` reads every field of the entry (`type` already read), puts the bodies it acts
  /// on into `bodies` (its ports in order, each a body of `m` with inertia) and returns the element,
  /// reporting every problem located (null when one was bad); `compile` is unused. Compiled after
  /// `gravity:` (m.gravity is set).
  std::shared_ptr<const Element> (*place)(FieldReader& f, const Model& m, std::vector<int>& bodies) = nullptr;
  /// Such a type's example bodies: the `bodies:` section (a YAML flow map's body) its example acts on.
  const char* example_bodies = "";
};

/// Every registered type, in the order of their files' names.
const std::vector<const ElementType*>& element_types();
/// The type named `name`, or null.
const ElementType* find_element_type(std::string_view name);

}  // namespace machdyn::detail

/// Registers an element type on one body (section `drives:`) from its own file
/// src/elements/types/NAME.cpp (NAME: the file's name).
#define MACHDYN_ELEMENT_TYPE(NAME, TYPE, COMPILE, EXAMPLE)                       \
  const ::machdyn::detail::ElementType& machdyn_element_type_##NAME() {          \
    static const ::machdyn::detail::ElementType kType{TYPE, &(COMPILE), "drives", 1, EXAMPLE}; \
    return kType;                                                                \
  }

/// Registers an element type between two bodies (section `links:`, `between: [A, B]`; its port 0
/// on A, port 1 on B) from its own file src/elements/types/NAME.cpp.
#define MACHDYN_LINK_ELEMENT_TYPE(NAME, TYPE, COMPILE, EXAMPLE)                  \
  const ::machdyn::detail::ElementType& machdyn_element_type_##NAME() {          \
    static const ::machdyn::detail::ElementType kType{TYPE, &(COMPILE), "links", 2, EXAMPLE}; \
    return kType;                                                                \
  }

/// Registers an element type under `links:` whose own fields name its bodies (ElementType::place)
/// from its own file src/elements/types/NAME.cpp; BODIES: its example's `bodies:`.
#define MACHDYN_PLACED_ELEMENT_TYPE(NAME, TYPE, PLACE, EXAMPLE, BODIES)                           \
  const ::machdyn::detail::ElementType& machdyn_element_type_##NAME() {                           \
    static const ::machdyn::detail::ElementType kType{TYPE, nullptr, "links", 0, EXAMPLE, &(PLACE), BODIES}; \
    return kType;                                                                                 \
  }
