#pragma once
// The generic plugins any fault detection problem needs, as one plugin set.

#include "ftsense/generic/attitude_from_imu.hpp"
#include "ftsense/generic/change_guard.hpp"
#include "ftsense/generic/cusum_detector.hpp"
#include "ftsense/generic/difference_residual.hpp"
#include "ftsense/generic/fault_merge.hpp"
#include "ftsense/generic/fault_classifier.hpp"
#include "ftsense/generic/fault_recovery.hpp"
#include "ftsense/generic/gain_isolator.hpp"
#include "ftsense/generic/load_apportioner.hpp"
#include "ftsense/generic/low_pass.hpp"
#include "ftsense/generic/orientation_to_rpy.hpp"
#include "ftsense/generic/physical_range_detector.hpp"
#include "ftsense/generic/plane_fit_residual.hpp"
#include "ftsense/generic/random_walk_fault_filter.hpp"
#include "ftsense/generic/rejoin_detector.hpp"
#include "ftsense/generic/signal_validator.hpp"
#include "ftsense/generic/signature_isolator.hpp"
#include "ftsense/generic/step_isolator.hpp"
#include "ftsense/generic/still_reading_isolator.hpp"
#include "ftsense/generic/stuck_hold.hpp"
#include "ftsense/generic/sum_constraint_residual.hpp"
#include "ftsense/generic/threshold_detector.hpp"
#include "ftsense/generic/unloaded_reading_residual.hpp"
#include "ftsense/generic/unread_load_isolator.hpp"
#include "ftsense/plugin_set.hpp"

namespace ftsense::generic {

using generic_plugins = PluginSet<DifferenceResidual, LowPass, ThresholdDetector, RandomWalkFaultFilter, FaultRecovery,
                                  OrientationToRpy, AttitudeFromImu, CusumDetector, SignalValidator,
                                  UnloadedReadingResidual, SumConstraintResidual, SignatureIsolator, FaultClassifier, FaultMerge,
                                  ChangeGuard, StepIsolator, GainIsolator, StuckHold, UnreadLoadIsolator,
                                  RejoinDetector, PhysicalRangeDetector, LoadApportioner, PlaneFitResidual,
                                  StillReadingIsolator>;

}  // namespace ftsense::generic
