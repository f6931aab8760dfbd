#pragma once
// Owning handles for MuJoCo model/data and loading a model from an MJCF string (no files).
#include <memory>
#include <stdexcept>
#include <string>

#include <mujoco/mujoco.h>

namespace ftsense::sim {

struct MjModelDeleter {
  void operator()(mjModel* m) const noexcept { mj_deleteModel(m); }
};
struct MjDataDeleter {
  void operator()(mjData* d) const noexcept { mj_deleteData(d); }
};
using MjModelPtr = std::unique_ptr<mjModel, MjModelDeleter>;
using MjDataPtr = std::unique_ptr<mjData, MjDataDeleter>;

/// Thrown when MuJoCo rejects generated MJCF (a programming error in the generator).
class ModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Compiles MJCF text through an in-memory virtual file system.
[[nodiscard]] MjModelPtr load_mjcf_string(const std::string& xml);

/// Id of a named MuJoCo object; throws ModelError if absent.
[[nodiscard]] int require_id(const mjModel* m, mjtObj type, const char* name);

}  // namespace ftsense::sim
