#pragma once
// The walking-biped virtual force sensor family (method.md sections 1-4) as one plugin set.

#include "ftsense/biped/contact_force_distribution.hpp"
#include "ftsense/biped/contact_force_fdi.hpp"
#include "ftsense/biped/foot_cop.hpp"
#include "ftsense/biped/leg_force_split.hpp"
#include "ftsense/biped/limb_inertia_correction.hpp"
#include "ftsense/biped/lipm_com_estimator.hpp"
#include "ftsense/biped/lipm_zmp.hpp"
#include "ftsense/biped/support_force_distribution.hpp"
#include "ftsense/biped/total_ground_force.hpp"
#include "ftsense/biped/zmp_from_contact_forces.hpp"
#include "ftsense/plugin_set.hpp"

namespace ftsense::biped {

using biped_plugins =
    PluginSet<LipmComEstimator, LegForceSplit, FootCop, ContactForceDistribution, ZmpFromContactForces,
              ContactForceFdi, SupportForceDistribution, TotalGroundForce, LipmZmp, LimbInertiaCorrection>;

}  // namespace ftsense::biped
