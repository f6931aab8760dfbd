#include "walk_instances.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "ftsense/io/csv_log.hpp"
#include "ftsense/pipeline.hpp"
#include "ftsense/reference_plugins.hpp"
#include "ftsense/sim/simulator.hpp"

namespace ftsense::peer_qp {
namespace {

Json read_json(const std::string& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return parse_json_text(text.str(), path);
}

biped::ContactGeometry stage_geometry(Pipeline& pipeline, std::string_view stage_name) {
  std::size_t index = 0;
  while (index < pipeline.stage_count() && pipeline.stage_name(index) != stage_name) ++index;
  if (index == pipeline.stage_count()) throw std::runtime_error("the config has no stage " + std::string(stage_name));
  const Json params = pipeline.stage(index).params_json();
  const Json& points = params.at("points");
  const Json& weights = params.at("weights");
  const auto n = static_cast<Eigen::Index>(points.size());
  biped::ContactGeometry geometry;
  geometry.points.resize(2, n);
  geometry.weights.resize(n);
  for (Eigen::Index l = 0; l < n; ++l) {
    const auto i = static_cast<std::size_t>(l);
    geometry.points(0, l) = points[i][0].get<double>();
    geometry.points(1, l) = points[i][1].get<double>();
    geometry.weights(l) = weights[weights.size() == 1 ? 0 : i].get<double>();
  }
  geometry.validate();
  return geometry;
}

}  // namespace

WalkInstances record_walk_instances(const std::string& source_dir, double seconds, std::uint64_t seed) {
  sim::Scenario scenario = sim::load_scenario(source_dir + "/configs/scenarios/clean.json");
  scenario.duration_s = seconds;
  std::stringstream csv;
  (void)sim::simulate(scenario, seed, csv);

  Pipeline pipeline = Pipeline::build(read_json(source_dir + "/configs/suralp.json"), reference_plugins::registry());
  WalkInstances walk;
  walk.geometry = stage_geometry(pipeline, "vfs_l");
  const biped::ContactGeometry right = stage_geometry(pipeline, "vfs_r");
  if (right.points != walk.geometry.points || right.weights != walk.geometry.weights) {
    throw std::runtime_error("vfs_l and vfs_r have different feet; the comparison assumes one geometry");
  }
  struct FootSignals {
    SignalRef fz, cop, forces, status;
  };
  const std::array<FootSignals, 2> signals{{
      {pipeline.signal("cop_l.normal_force"), pipeline.signal("cop_l.cop"), pipeline.signal("vfs_l.forces"),
       pipeline.signal("vfs_l.status")},
      {pipeline.signal("cop_r.normal_force"), pipeline.signal("cop_r.cop"), pipeline.signal("vfs_r.forces"),
       pipeline.signal("vfs_r.status")},
  }};

  io::CsvLogReader log(csv, "simulated walk");
  std::vector<std::vector<std::size_t>> columns;  // per pipeline input, its log columns
  for (const auto& input : pipeline.inputs()) {
    columns.emplace_back();
    for (const auto& name : input.columns) columns.back().push_back(*log.find_column(name));
  }
  std::vector<double> row;
  pipeline.reset();
  while (log.next(row)) {
    for (std::size_t i = 0; i < columns.size(); ++i) {
      const auto values = pipeline.input_values(i);
      for (std::size_t c = 0; c < columns[i].size(); ++c) values[c] = row[columns[i][c]];
    }
    pipeline.step(row[0]);
    ++walk.ticks;
    for (std::size_t foot = 0; foot < 2; ++foot) {
      const FootSignals& s = signals[foot];
      const auto status = static_cast<biped::ContactQpStatus>(pipeline.values(s.status)[0]);
      if (status != biped::ContactQpStatus::optimal) continue;
      const auto cop = pipeline.values(s.cop);
      const auto forces = pipeline.values(s.forces);
      walk.feet[foot].push_back({pipeline.values(s.fz)[0], {cop[0], cop[1]}});
      walk.pipeline_forces[foot].insert(walk.pipeline_forces[foot].end(), forces.begin(), forces.end());
    }
  }
  return walk;
}

}  // namespace ftsense::peer_qp
