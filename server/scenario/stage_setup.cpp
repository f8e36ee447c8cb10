#include "server/scenario/stage_setup.h"

#include <string>

namespace cascade {

namespace {

StagePlan stage_plan(const v1::Stage& stage) {
  StagePlan plan;
  switch (stage.kind_case()) {
    case v1::Stage::kGeostatic: {
      const auto& g = stage.geostatic();
      plan.kind = StageKind::geostatic;
      plan.name = "geostatic";
      if (g.force_ratio() > 0) plan.geostatic.force_ratio = g.force_ratio();
      if (g.speed() > 0) plan.geostatic.speed = g.speed();
      if (g.local_damping() > 0) plan.geostatic.local_damping = g.local_damping();
      if (g.max_steps() > 0) plan.geostatic.max_steps = g.max_steps();
      break;
    }
    case v1::Stage::kPoreWater: {
      const auto& w = stage.pore_water();
      plan.kind = StageKind::pore_water;
      plan.name = "pore_water";
      if (w.initial_dt() > 0) plan.pore_water.initial_dt = w.initial_dt();
      if (w.min_dt() > 0) plan.pore_water.min_dt = w.min_dt();
      if (w.max_dt() > 0) plan.pore_water.max_dt = w.max_dt();
      if (w.pressure_tolerance() > 0) plan.pore_water.pressure_tolerance = w.pressure_tolerance();
      if (w.max_iterations() > 0) plan.pore_water.max_iterations = w.max_iterations();
      if (w.water_content_change() > 0) plan.pore_water.water_content_change = w.water_content_change();
      break;
    }
    case v1::Stage::kDynamic:
    case v1::Stage::KIND_NOT_SET:
      plan.kind = StageKind::dynamic;
      plan.name = "dynamic";
      break;
  }
  if (!stage.name().empty()) plan.name = stage.name();
  if (stage.end().has_time()) plan.end_time = stage.end().time();
  const auto& band = stage.end().yield_band();
  if (band.ratio() > 0) plan.yield_band.ratio = band.ratio();
  plan.yield_band.volume = band.volume();
  plan.yield_band.connected = band.connected();
  plan.yield_band.span = band.span();
  if (stage.end().has_motion()) {
    const auto& m = stage.end().motion();
    plan.motion = MotionTrial{};
    if (m.speed() > 0) plan.motion->speed = m.speed();
    if (m.duration() > 0) plan.motion->duration = m.duration();
    plan.motion->interval = m.interval();
  }
  return plan;
}

}  // namespace

std::vector<StagePlan> stage_plans(const v1::ScenarioSpec& spec) {
  std::vector<StagePlan> plans;
  for (const auto& stage : spec.stages()) {
    plans.push_back(stage_plan(stage));
    if (plans.back().yield_band.connected && !(plans.back().yield_band.span > 0))
      plans.back().yield_band.span = 10 * spec.dp();
  }
  return plans;
}

double stage_frame_interval(const v1::ScenarioSpec& spec, int stage) {
  if (stage < spec.stages_size() && spec.stages(stage).output_interval() > 0) return spec.stages(stage).output_interval();
  return spec.output().interval();
}

double stage_probe_interval(const v1::ScenarioSpec& spec, int stage) {
  if (stage < spec.stages_size() && spec.stages(stage).probe_interval() > 0) return spec.stages(stage).probe_interval();
  if (stage < spec.stages_size() && spec.stages(stage).output_interval() > 0) return spec.stages(stage).output_interval() / 10.0;
  return spec.output().probe_interval() > 0 ? spec.output().probe_interval() : spec.output().interval() / 10.0;
}

std::unique_ptr<Engine> make_case_engine(const v1::ScenarioSpec& spec, const EngineConfig& config,
                                         const HostParticles& particles, const EngineMaker& make) {
  std::unique_ptr<Engine> dynamic = make(config, particles);
  if (spec.stages_size() == 0) return dynamic;
  std::vector<double> forcing_times;
  for (const auto& point : spec.hydraulics().rainfall()) forcing_times.push_back(point.time());
  return std::make_unique<StagedEngine>(std::move(dynamic), config, stage_plans(spec), std::move(forcing_times));
}

}  // namespace cascade
