#pragma once
// Values a pipeline config defines once and uses in several places (JSON itself has no
// references). A config may hold a top-level object
//
//   "definitions": { "sole_outline": [[0.112, 0.037], [0.112, -0.037], ...] }
//
// and, anywhere else, an object whose only key is "$ref" with a JSON Pointer to one of them,
//
//   "points": { "$ref": "#/definitions/sole_outline" }
//
// which stands for a copy of that value (the JSON Schema / OpenAPI convention, so editors and
// readers know it). A definition may use other definitions; a cycle, an unknown name, a "$ref"
// beside other keys or a pointer outside "#/definitions/<name>" is an error at its JSON Pointer.

#include "ftsense/diagnostics.hpp"
#include "ftsense/params.hpp"

namespace ftsense {

// The config with every reference replaced by its definition ("definitions" itself is kept, as
// written). Problems go to `diag`; the references they concern are left in place.
[[nodiscard]] Json resolve_definitions(const Json& config, Diagnostics& diag);

}  // namespace ftsense
