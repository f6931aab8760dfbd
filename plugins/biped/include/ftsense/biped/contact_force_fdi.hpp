#pragma once
// Fault detection, isolation, classification and recovery for the contact-point force sensors of
// a legged robot's feet (any number: a biped's two soles of four pads, a quadruped's four point
// feet of one sensor each), from what is known accurately (beyond the paper; method.md section 7).
//
// The paper judges each point against a per-point virtual force that is off by ~100 N in stance.
// This plugin uses three facts that hold to a few newtons instead:
//   1. A pad that kinematics places above the ground carries nothing: pad height
//      h_j = (o_f + R_f [x_j, y_j, 0])_z > airborne_height_m  =>  N_j = 0 (exactly, in the
//      simulator; within noise on a robot).
//   2. All pads together carry the total vertical force: sum_j N_j = F_z = m (R_wb f_imu)_z, up to
//      the unmodelled limb dynamics (about 20 N RMS on the simulated SURALP). A single-channel
//      fault of size f shifts the sum residual r = sum_j N_j - F_z by f.
//   3. A healthy pad's force is continuous: it does not jump by tens of newtons in one tick while
//      the total force stays put, and a noisy sensor never repeats a value exactly.
//
// Thresholds in newtons follow from what a user knows, unless given: the readings' error sigma,
// sqrt(noise_std_N^2 + resolution_N^2 / 12) (noise and quantisation: a coarse quantiser that the
// noise cannot dither still steps by q between levels under a steady load): airborne 4 sigma,
// its clearing 2 sigma, jump 10 sigma, jump confirmation
// 12.5 sigma, spike 30 sigma; and the robot's weight W = m g (weight_N): sum_threshold_N 7 % of W
// (the bound of the virtual total force's low-passed error), gain_min_load_N 2.5 % of W. The
// same config then holds for a 13 kg or a 114 kg robot.
//
// Tests, per channel j, each tick (thresholds are parameters):
//   invalid   N_j not finite.
//   frozen    N_j on one quantisation level (|N_j,k - N_j,k-1| <= q / 2, q = resolution_N; 0:
//             exact repeats) for n_f ticks, n_f the run a healthy reading makes with probability
//             below alpha = T / false_alarm_interval_s: noise of std sigma (noise_std_N) keeps a
//             reading on its level with probability at most p = erf(q / (2 sqrt(2) sigma)) per
//             tick (a load at the level's centre), so n_f = max(frozen_min_s / T, ln alpha / ln p)
//             (5 N steps and 2 N noise: p = 0.79, 77 ticks at 1 kHz). Where n_f would exceed
//             1e5 ticks (a quantiser coarser than its noise dithers: a steady load sits on one
//             level for ever), a reading alone cannot tell a stuck sensor, and this test is off:
//             the sum residual and the follow test judge it against its load, and a reading at
//             the top of a stated range (upper_limit_N - q/2) is saturation on its tick. (A noise
//             stated far too small, millinewtons written as newtons, turns the test off too.)
//             An unloaded pad (airborne,
//             or left no load by the others: leave-one-out force below airborne_threshold_N) that
//             reads its zero level (|N_j| <= q / 2) is not evidence (a sensor may clip at 0).
//             Nor is a zero reading where the load may be within the clamp of such a driver: a
//             driver that reports any reading below c = zero_clamp_N (0 when not known) as exactly
//             0 makes a zero say only that the pad carries less than c, so a zero is evidence
//             only while the leave-one-out force, whose error the sum residual's bound
//             sum_threshold_N covers, puts the load above c + sum_threshold_N (a pad that rolls
//             off, or lifts before its foot's kinematics says so, reads exact zeros for tens of
//             ticks while its leave-one-out force still shows a few newtons). A sensor stuck at 0
//             under a lighter load is off by less than that bound. Saturation when the value is at the top of the range (upper_limit_N - q/2,
//             when given), or a load (> airborne_threshold_N) that is the largest the channel has
//             shown, or when the channel sticks again at the value of its previous stuck episode
//             (a clipped load returns to the same ceiling). A channel found stuck under load keeps
//             that level C until it reads above C + q/2: back at C for two ticks on the ground
//             while its leave-one-out force exceeds C by sum_threshold_N, it is saturated on that
//             tick, not n_f ticks later (a clipped sensor clips at the same level each stance; a
//             frozen one does not leave and return).
//   spikes    N_{k-1} deviates from both neighbours by > spike_threshold_N while they agree, and
//             its foot's summed reading spikes the same way by at least half as much (load that
//             rocks between two pads of a sole for a tick, a heel pad chattering on and off the
//             ground, leaves the sum smooth; a sensor's spike is in it), and no other pad of its
//             foot that reads its load (healthy or corrected; a gain's as N / k) made the opposite
//             excursion beyond its noise, z sqrt(3/2) sigma_x, on that tick and came back (moved
//             over the two ticks by less than that excursion; a step moves by twice it): load went
//             from one pad to the other and back, though an impact may shed part of it from the
//             sum (a heavy biped's heel chatters so for longer than a landing's guard; sensors'
//             spikes are independent), and no other pad of its foot reads other than its load
//             (substituted under load, or a noise burst: its
//             reading misses or swamps the load it trades with this pad, so neither the sum nor
//             this pad tells a spike then; the noise test alike, so a second noise burst on that
//             foot waits for the first to clear; a channel already flagged is judged on, so that
//             it clears) (not
//             within touchdown_guard_s of a touchdown, nor while the pad rings after its own
//             landing, as for jumps below: a landing heel rings like a spike); the flag stays h after the last spike. Spikes of a faulty
//             sensor come at random (rate lambda, exponential gaps), so once an episode has n >= 2
//             spikes over D seconds (lambda^ = (n - 1) / D), a gap of h = ln(1 / p_gap) / lambda^
//             says the process has stopped: a running one leaves so long a gap with probability
//             p_gap (spike_gap_probability). h stays within [clear_s, spike_hold_s]; the first
//             spike of an episode (rate unknown) holds spike_hold_s. D and the gap count only the
//             time the test could see (outside the guards), so blind stretches bias neither
//             (the rule is generic/spike_episode.hpp's, shared with signal_validator).
//             While the channel is flagged as a noise burst, its spikes are that noise's tails:
//             the noise test alone clears it, and the spike episode ends with it.
//   noise     over noise_window_s, more than half of the second differences d2 exceed
//             noise_factor * sqrt(6 (sigma^2 + q^2 / 4)) (their healthy standard deviation, q / 2
//             the worst quantisation error) while the foot's summed reading is as rough (its d2
//             above sqrt(n) times that: load rocking between the pads of a foot cancels there, a
//             pad's own noise does not), and the window is rough like white noise rather
//             than smooth like a load: sum d2^2 > sum d1^2 (white noise: 6 sigma^2 against
//             2 sigma^2; a load moving at the tick rate, as at 200 Hz: d2 << d1); not raised
//             within touchdown_guard_s of any foot's touchdown (a landing foot bounces on its
//             pads, and at a fast gait logged at 200 Hz the other foot's pads ring with it); a
//             d2 whose lowest reading is at the air level (within airborne_threshold_N of 0: a
//             contact does not pull) inside the pad's own landing guard is not counted, unless
//             the channel is flagged noise (its contact chatters as its foot rolls onto it: a
//             heavy robot's outer heel lets go every 6 ms).
//   airborne  |mean N_j| > airborne_threshold_N, the mean of the readings taken once the pad has
//             been airborne for airborne_settle_s, over at least 0.02 s and 10 readings:
//             offset, drift or frozen-at-load; the mean measures the fault directly.
//   jump      |N_j,k - N_j,k-1| > jump_threshold_N and the reading is as far from its linear
//             prediction 2 N_j,k-1 - N_j,k-2 (a step is a surprise, a fast healthy load change
//             at a slow log rate is not), with no foot touching down within
//             touchdown_guard_s (a landing impact jumps pads and, unseen by the trunk IMU, the
//             sum residual; a rolling foot's pads change only a few N per tick), nor while the
//             pad rings after its own landing (a pad on the ground left no load by the others, on
//             its zero level, that takes load back: tens of N in one tick at 200 Hz, chatter on
//             and off; "no load": its leave-one-out force within airborne_threshold_N, or, for a
//             healthy pad at its zero level for two ticks, within the total force's error): until
//             its changes have stayed below jump_threshold_N for jump_window_s, or while it steps
//             to or from its air level (its contact lost and made again: a heavy robot's heel
//             bounces 8-10 ms apart), at most touchdown_guard_s after the landing (a ring that has
//             died out is over),
//             nor on a tick another pad of its foot lands so or, ringing, jumps (a heel landing
//             late jolts its neighbours on that tick, which F_z misses as it does a foot's
//             impact; a pad chattering on and off trades its load with them);
//             a channel flagged as a noise burst is no candidate (its swings are that fault);
//             no group forms while the corrected sum residual (low-passed at 10 Hz, last tick's)
//             is beyond sum_threshold_N (a fault no test has named yet: loads moving into or out
//             of it step the residual as a sensor would), nor when a pad of a member's loaded
//             foot may have taken or given the load unread: a healthy pad on the ground at its
//             air level that has carried nothing since its foot landed (or, when two or more of
//             the foot's candidates are healthy, any healthy pad on the ground at its air level: a
//             pad that rolled off within the stance and died there; one dead pad is the fewer
//             faults, where against one sensor's step or a fault's end it is not; such a pad is
//             marked as handed load, the unread-load test's evidence), while the pads' sum falls
//             (its own landing, as a heel rolls onto a dead sensor: the neighbours' steps are the
//             load they hand it), or a stuck reading (frozen, saturated) while the sum falls or
//             while it carries load, or an offset the air test measured whose reading has not yet
//             spanned follow_ratio of its load's move (a reading frozen at a load reads as that
//             offset in the air; its correction then says nothing of its load) (the unread-load,
//             still-reading and follow tests judge that pad), nor within jump_window_s after a
//             loaded pad's gain correction (its reading taken as x / k in this residual) was set,
//             refitted or dropped, stepping the residual by |x (1 / k_new - 1 / k_old)| >=
//             jump_confirm_N, and a pending group whose windows such a change falls in is
//             dropped; nor on or within a jump window after a tick where a healthy reading sat
//             on a level it was found stuck at under load before (within q / 2: a clip's
//             ceiling, `on_ceiling`). Its load is not read there (a clip hides what it carries
//             beyond the ceiling), and its leaving the level steps the sum residual and its
//             foot's plane by what it hid, as a neighbour's step would: a pad clipped at its
//             stance peak for a few ticks as the other foot lands, then left as its foot
//             unloads, had its clip's end taken for a neighbour's step by the plane, stride
//             after stride. So a pending group such a tick falls in is dropped, the plane takes
//             no foot with such a pad as in full contact, and a jump left to the sum residual
//             after a guard is dropped when such a tick fell since the window before the guard;
//             confirmed when the sum
//             residual steps over jump_window_s by the net jump of the channels that jumped in
//             that tick (same sign, both >= jump_confirm_N, within max(jump_confirm_N, 50 %) of
//             each other): an abrupt fault, isolated at once. A member whose reading is back
//             within half its jump of the reading before, on the next tick, leaves the group (and
//             its foot's plane group below): it spiked for a tick, which at 200 Hz moves a 2-tick
//             window's mean by half the jump. (Not against the trend: a noise burst's trend is
//             its last swing. A step against a pad unloading by half the step per tick leaves
//             the group too, and is left to the other tests.) The residual takes a spiking channel as the median of its last three
//             readings (a 250 N spike moves a 10 ms mean by 50 N at 500 Hz); the median lags a
//             step by a tick, so once the next reading shows the step stayed (no return within
//             half its rise) the last tick's residual takes the reading (a spiking heel landing at
//             200 Hz otherwise confirmed a neighbour's load shift). A confirmed jump
//             of a channel that was flagged when it jumped is no onset, even if a test cleared the
//             flag while the group was pending (a stuck output's step back to its load, which the
//             follow test re-admits on that very step). While a loaded channel is
//             substituted from the total force (frozen, saturated, invalid; not a noise burst or spikes,
//             which are recovered from their own readings), the sum carries its
//             unmeasured changes, and while a loaded channel reads a noise burst, its swings: so
//             confirmation then takes 3 x jump_confirm_N (with a channel substituted, at least
//             sum_threshold_N, the bound of the total force's error its share carries: a
//             substituted heel chattering on and off hands 40-55 N to its neighbours within a
//             tick; so while any pad is substituted, a step under sum_threshold_N, an onset or an
//             end, is left to the air test), and none is confirmed while a substituted channel's
//             foot rolls on or off.
//             Inside a touchdown guard, with the soles' layout given (`points`), a jump is
//             confirmed by its foot's plane relations instead (unmeasured_contact_loads.hpp: a
//             rigid sole's loads are affine in the pads' positions, through an impact too, which
//             the sum residual cannot see past): the foot in full contact (every pad on the
//             ground, loaded, read as it is or corrected) over both windows, each relation
//             stepping by sum_j w_j jump_j within max(z sigma, 50 %), and the step and that
//             expectation both beyond z sigma in the relations' norm; sigma the window step's
//             RMS measured on the log's healthy full-contact ticks (at least 100), z the
//             two-sided normal quantile of alpha = T / false_alarm_interval_s; a group of several
//             pads only if no member alone explains the step within z sigma (and beyond z on its
//             own): one relation cannot tell which of them stepped, and a lifting sole's pads fall
//             as one while its plane departs by about one pad's share (none is named then; a
//             fault among them waits for another test, the air test at the swing). A jump the plane
//             cannot judge (its foot not in full contact over both windows: a heel rocking on
//             and off as the foot lands) is judged by the sum residual once the guard is over and
//             a jump window has passed: the residual's step from its mean over the jump window
//             before the guard must match the net jump of the pad's foot's candidates of that
//             tick (as a group's must, within max(jump_confirm_N, 50 %)), beyond
//             max(jump_confirm_N, z_g s_g), s_g the RMS of that step over the walk's healthy
//             guards so far (at least 5; a landing moves the total force's error by tens of
//             newtons, where a jump window barely does; each step counted clipped at the bar once
//             five are, so that a fault not raised there cannot lift the bar for the rest of the
//             walk), z_g the two-sided normal quantile of alpha = touchdown_guard_s /
//             false_alarm_interval_s (one decision per landing). A jump still pending when the
//             next guard begins is dropped (it would be judged across two landings).
//             Only a step between two loads (above airborne_threshold_N before it and a jump
//             window after): one from or to the zero level is the pad's contact coming or going.
//             Raised as an offset of its jump only when its plane group is the pad alone (a
//             neighbour stepping on that tick, qualifying or not, makes it unnameable) and it is
//             the one group that matches, no end is pending, no flag changed since the guard began (an
//             offset is in the residual as read: one raised meanwhile moved it), and every
//             channel is unflagged or an offset or drift (s_g is learnt on guards with none
//             flagged; a substituted, gain-corrected or noisy channel moves the residual by what
//             it does not read). Point feet have no plane relation, and none of this.
//             Inside another foot's touchdown guard, a pad not landing itself that steps back by
//             its fault's size (|jump + b| < 0.4 |b| + jump_confirm_N, b the fault's size now),
//             where that size is settled (measured in the air, or a gain), may be the fault's
//             end: once the guard is over and a jump window has passed, the sum residual must have
//             stepped from its mean over the jump window before the guard by what the end implies
//             (-b; a gain: -(1 - 1/k) x_before / k), within max(jump_confirm_N, 50 %), beyond
//             the confirmation step: then the channel is re-admitted. The step itself is not the
//             measure: at a landing the pad also hands load over (tens of N in a tick at 200 Hz).
//             A healthy channel's step while a group is pending (the other foot's pads unloading
//             at its lift-off, and a fault starting within that jump window; a member of the
//             pending group stepping again counts too, and a flagged member's step back by its
//             fault's size, its end) forms a late group (one at most); the two
//             are decided together a jump window after the late jump (the first group's window
//             holds the late jump, so it cannot be judged alone): the residual's step from its
//             mean before the first group's jump must match the first group's sum, the late
//             group's, or both (each group's own sum at least the confirmation step), and the nearest
//             match that passes is taken. A late group forms only while no fault's end is
//             pending, and steps while it is pending join none. A flagged channel that steps
//             back by its fault's size while a group is pending (a landing foot's pads jumping
//             as it rolls on, the fault ending in the same jump window) is judged on its
//             own: a jump window after its step, the residual must have stepped from its mean
//             before the group's jump by its step, plus the group's if that was confirmed (a
//             dropped group drops it). With more than one such end pending, none is re-admitted
//             this way (one residual step could match each of two). Inside the guard, the
//             foot's plane relations (`points`) judge a landing foot's pads first.
//   gain      (stance regression) the corrected sum residual r = sum_i N^_i - F_z fitted, channel
//             by channel, by r ~ b_j + beta_j N^_j over an exponential window of gain_window_s
//             (beta_j = cov(r, N^_j) / var(N^_j), weighted alike). A channel reading k times its
//             force makes r = (1 - 1/k) N^_j, an exact fit; a constant r (an offset anywhere, or
//             the reference off) is b_j, not a gain: through the origin it would be fitted by any
//             pad loaded most of the time. A healthy walk leaves |beta_j| < 0.05 with under 15 %
//             of r explained (the limb dynamics). The channel whose fit explains the largest share
//             of r's variation is raised as a gain fault when that share exceeds gain_explained and
//             every other channel's by gain_isolation_margin (the pads of one foot load together,
//             and the sum cannot see moments, so a fault on one is often fitted nearly as well by
//             its neighbour: then nothing is blamed and `unisolated` is raised instead) and
//             |beta_j| > gain_threshold, with k = 1 / (1 - beta_j), and its RMS load over the
//             window is above gain_min_load_N, and (a new flag only) the same fit within each
//             stance of the pad (each stance centred on its own means) has beta of that sign and
//             above gain_threshold too: an offset that begins as its pad lands (r = 0, N^ = 0 in
//             the air; r = b, N^ = N + b after) lies on a line across the landing, but within a
//             stance r stays b while N^ moves (a confirmation only: within a stance the limb
//             dynamics follow the loads, too weak alone). A new flag whose implied load
//             N^_j - r stayed within gain_min_load_N RMS over the window (a robot standing while a
//             pad drifts: r and N^_j rise together, beta near 1, k = 10 from the clamp) is no
//             gain, which cannot be told from an additive error without load motion: it is an
//             additive fault, typed from the sum residual's blocks since the last flag change
//             (generic::onset_shape: a ramp raises a drift on the blocks' line, a step an offset
//             of the corrected residual's level now), and none at all when that level is back
//             within z of its noise of the healthy level (the fault ended before the window judged
//             it), or when no healthy block precedes it since the last flag change, the blocks'
//             noise is not measured yet (the next window judges again), or another channel is
//             flagged (its correction is in the residual, and a drift beside it could not be
//             held at its plateau). The
//             same test refines k on the corrected residual
//             and re-admits the channel when k comes back within gain_threshold / 2 of 1, or, by
//             model comparison (no isolation needed), when it carried load (RMS above
//             gain_min_load_N) and its reading taken as it is leaves no more residual power than
//             its correction does over the gain window since the correction was set (two or
//             more gains, none of which wins alone as each keeps the others' corrections in the
//             residual: all of them together, when their readings taken as they are leave a
//             quarter of the power of all their corrections, over the ticks since the set last
//             changed (a gain window at least), each having carried load over the window); and
//             within one stance, once it has clear_s of usable ticks, when the correction leaves
//             4 times the residual power the reading leaves as it is, and moved the reading by
//             gain_min_load_N RMS or more: the two explanations of that stance, compared (for a
//             gain also over its own foot's touchdown guard alone, while it is the one
//             correction, judged once on the first usable tick after the guards, within
//             jump_window_s of the last, before the jump test resumed there takes the moves of a
//             correction gone wrong in the air for its neighbours' jumps: over the whole guard a
//             short pulse of the impact's error is diluted, but an error of the total force over
//             the guard of the correction's sign and two thirds of its size drops a gain still
//             right, as it would over clear_s after the guard; for an
//             offset too, whose end stepped under jump_threshold_N; an offset raised by a jump
//             under load and not yet seen in the air must beat the gain its onset implies too,
//             which must have moved the reading by gain_min_load_N RMS), over the stance so far or
//             (an offset) since the CUSUM of the reading's lead was last at 0 (a fault that ends
//             late in a long stance); a drift, whose slope is extrapolated through the stance and
//             may grow wrong while it goes on, only since that CUSUM was last at 0 and only once
//             the reading as it is stayed flat over a window that could have shown the drift
//             going on at a quarter of its fitted rate (StancePowers::trend: neither the
//             window's slope nor its bend beyond relation_z_ of its standard error, fitted on the
//             ticks' times, not their count: a drift grows with time, and the ticks the window
//             takes have gaps where none is usable; a window that shows either is closed and the
//             next judged afresh), or, for a drift that ended
//             at once, once its reading sits on the load: the reading and its foot's summed
//             reading stepped back by about its correction c on one tick (|dx + c| < |c| / 2,
//             |c| beyond relation_z_ sqrt(2) sigma_x, under any jump threshold) within a jump
//             window before the ticks since that CUSUM was last at 0 began, and over those ticks
//             the sum residual r_raw (as the jump test takes it) stepped by as much from its
//             level before (a first-order low-pass of time constant clear_s over at least
//             2 clear_s of usable ticks in a row), |c| / 2 beyond relation_z_ of that step's
//             standard error s sqrt(v + 1 / n) (s the window's scatter about its line and bend,
//             v the level's variance in units of s^2, about 1 / (2 n_c - 1) with
//             n_c = clear_s / T, n its ticks), its mean lead within gain_min_load_N, no slope or
//             bend beyond relation_z_ at whatever precision the window has, never found sloped
//             (a drift regrowing after a fade never stepped; load moving between a foot's pads
//             leaves its summed reading alone, load moving between feet the residual): a pad that stays
//             loaded to the end of a log has no next swing to judge it; only while it is the one correction
//             the residual carries (with two, the one still faulty can win first; a pad in the
//             air, recovered as 0 whatever its correction, carries none), and over those ticks
//             only: a tick with two restarts the sums (else they would be judged once the other
//             lifts or ends). A drift whose
//             reading stays flat over such a window of its stance (the same test, clear_s at
//             least), after a window of that stance in which it rose the drift's way, but off its
//             load by more than gain_min_load_N, the window's mean of r_raw, has stopped at that
//             level (a plateau): held as an offset there (hold_as_offset), not re-admitted by
//             the comparison once its extrapolated correction has overshot. A drift raised from
//             the residual's ramp on a still load (gain test, above) rose in its stance already,
//             and its plateau, taken from the residual's healthy level it was raised on (the
//             total force's bias stays in a standing stance), needs only to be off by z of the
//             residual's measured noise (plateau_bar), within gain_min_load_N at most: the robot
//             stands, and the walking stance's margin is not the error of its standing residual. A
//             gain that ended in the air, or a gain inferred in the air from an offset that ended
//             there (both read 0 in the air), would otherwise scale a healthy reading by 1 / k
//             through the next stances until the window decides. The window
//             restarts after every decision, and when the offset-or-gain test or the air test
//             below re-types an offset as a gain (its residuals took that channel as x - b: k
//             refined on them would fit the change of correction), and takes no tick while a loaded channel is
//             substituted from the total force (which absorbs the residual) or within
//             touchdown_guard_s of a touchdown (impacts).
//             A gain that begins in the air lands reading k N with no jump, and the window then
//             holds the stances before it, in which its pad carried load with r at 0: mixed
//             with them its fit is flat (0.3 % of r explained in a walk where it explained
//             99.6 % over its first stance), and it waited seconds for them to be forgotten.
//             So the same sums are kept beside it from where the low-passed residual left
//             sum_threshold_N with no channel flagged (`unisolated`; it stays open while the
//             residual returns within its bound, as a gain's does in every swing), closed by
//             any flag and after 3 gain windows, and a new gain is raised from them by the same
//             tests (share explained, its isolation margin, |beta|, the stances' confirmation, a
//             load that moved) once the best channel's point has closed a stance within them and
//             been in the air clear_s (weighted alike) since the first such stance: a gain reads 0 there as its load does, where an
//             additive fault's residual stays. Or without waiting for that air, over clear_s of
//             the window at least, by what a gain begun in the air is: its pad read its air level
//             and took no step, so r = b + beta N^_j with |b| <= sum_threshold_N (the residual at
//             zero load) and beta < 1 (k > 0; beyond, on a reading positive on the whole, the
//             reading would have the wrong sign). Only such fits are candidates in this window
//             (before and after the swing alike), and the
//             best must stand out by gain_isolation_margin of every other channel's fit, one of
//             a gain or not (a load shifting between the feet with the total force's error fits
//             the other foot's pads with an intercept: that explanation rivals it); and no healthy
//             reading may have stayed still on the ground within the window (its power about
//             each stance's mean, over its point's ground ticks, under follow_ratio^2 of r's
//             centred power): a stuck sensor whose load is r makes its neighbours' fits gains
//             until a swing tells them apart. In both windows a channel under gain_min_load_N
//             RMS is not blamed but still competes for isolation: at the end of a stance every
//             pad of the foot unloads alike, and a loaded healthy neighbour was blamed for what
//             the gain's own pad explained better. Not a restart of the gain window: a full
//             window after the onset delayed gains that the window found within a second.
//   follow    a channel raised as offset or drift whose smoothed reading spans less than
//             follow_ratio of what its leave-one-out force (smoothed alike) spans since, once that force has moved
//             by 2 sum_threshold_N (beyond its own error), both spans taken from when the
//             smoothing has settled after the flag was raised (five time constants of its 10 Hz
//             low-pass, so the step that raised it is not counted): the reading does not follow the load,
//             a frozen output that keeps its noise; re-typed frozen and substituted. Re-admitted
//             when the reading spans half the force's move again, each move of 2 sum_threshold_N
//             judged on its own (the span restarts after each, so a reading that follows again
//             need not match the moves it missed while frozen), or at once when the reading itself
//             spans sum_threshold_N and at least half the force's move so far (no stuck sensor's
//             noise spans that; the force need not first move twice its error).
//   still     (no flag yet) a reading that stays still while the load it should carry moves: a
//             frozen output that keeps its noise, found in stance. One window for all channels:
//             while the corrected sum residual r, low-passed at 10 Hz as the readings are, moves
//             by sum_threshold_N (the bound of the total force's error e; the fault-free walks and
//             crawls of the demo and of tools/unseen_walks.py raise no flag with it), a channel
//             stuck at c makes r = c - N_j + e, so
//             its load moved by that much unread. The channels on the ground and not flagged
//             throughout the window whose smoothed reading spans under follow_ratio of r's move,
//             and whose leave-one-out force x_j - r (its load, were it stuck; smoothed) is above
//             -airborne_threshold_N (a pad only pushes; one stuck where its load came to 0, a
//             foot about to lift, is one), are the candidates: exactly one is raised frozen (and
//             re-admitted by the follow test); two or more cannot be told apart (a steadily
//             loaded pad reads still too), and none is blamed. A pad of a foot within its
//             landing's touchdown_guard_s is counted but not named (a sole takes its load pad by
//             pad: a toe at its air level beside a loaded heel). The window is at least the
//             smoother's settling (five time constants) long, and restarts, a settling later,
//             when F_z or a reading is unknown, a channel steps (the jump test's: an onset it did
//             not judge; but not an unflagged pad of a foot within its landing's guard taking its
//             load, so that a window holds the load a landing moves off the other foot, the move
//             that shows a stuck pad there), a flag changes, or a loaded channel is flagged as
//             anything but drift, spikes or an offset told from a gain (a gain's wrong k, an
//             offset that may be a gain, or a substituted share moves r with its load, as a stuck
//             neighbour would).
//             That window holds what the stuck reading did before it stuck (a pad frozen at the
//             load it had just risen to spans that rise), and names no one. So beside it, short
//             windows open in turn every half settling, four at a time (each lives two
//             settlings): one begins within half a settling of any onset. Judged alike, but a
//             tenth of a second is short for slow loads and may hold a reading's last move before
//             it stuck (a saturation's ceiling reached): there a reading's span is taken only
//             since the residual was last within follow_ratio x sum_threshold_N of the extreme it
//             moved away from (its noise does not reset that start), a reading is ruled out only
//             if that span is at least twice the stuck band b as well, and the one candidate is
//             named only if its span over the whole window is at most b, b = q + 8 sigma
//             sqrt(a / (2 - a)) (a stuck reading's noise after the low-pass y += a (x - y),
//             +-4 sigma, and a quantisation level).
//             The decision needs the tick's residual, known with its outputs: the flag shows
//             from the next tick. Its known limit: with the reference itself moving and one
//             reading still (steadily loaded), that reading is taken as stuck.
//   unread    (no flag yet) a pad that reads nothing of the load it lands on: a dead sensor at its
//             air level, which the still test does not name while its foot lands. While the smoothed
//             residual r (as above) stays below -(sum_threshold_N + zero_clamp_N) (the pads read
//             short of F_z by more than its error and a clamped zero can hide), and exactly one
//             pad of the robot (of the strongest kind below) is on the ground, not flagged, with
//             its smoothed reading within +-airborne_threshold_N while a healthy neighbour on its
//             foot reads above it, that pad is the candidate, if r was within +-sum_threshold_N at some tick since its foot
//             landed (a shortfall from before is another fault's, a gain elsewhere), the pad has
//             not read above the air level since its foot landed (a dead pad that lands) or, where
//             no such pad stands, since r was last within that bound, having been handed load
//             since it last read any (its foot's healthy neighbours stepped together while the sum
//             fell, a group the jump test left unnamed for it): one that rolled off within the
//             stance and died at its air level takes its load back unread, where a lifting sole's
//             pads, which read their loads as they unload one by one, are normally handed nothing
//             and are no candidates), and that landing's touchdown_guard_s is over (an impact's error
//             in F_z); held for the smoother's settling (five time constants), it is raised
//             frozen (re-admitted by the follow test). Two such pads (a sole on its heel) cannot
//             be told apart, and neither is blamed. Not judged while a channel on the ground is
//             flagged as anything but offset, drift or spikes (a substituted share absorbs r),
//             nor while the gain test's fit stands unisolated. Point feet (one channel per foot)
//             have no neighbour and are not judged. Its known limit: a shortfall that begins
//             after the landing from another cause (the reference, a fault not yet seen) and
//             lasts the settling is taken as that pad's.
//   offset or gain  a jump on a loaded pad (load L0 > gain_min_load_N before it) is an offset
//             b or a gain k = 1 + b / L0 alike at its onset; as the load moves they part. Over the
//             follow test's span, the corrected sum residual r (the channel taken as x - b) and
//             r - (x - b) + x / k (taken as x / k) accumulate their power (not within
//             touchdown_guard_s of a touchdown: the impact moves r as the load shifts between the
//             feet, which a gain of the unloading pad mimics); once the leave-one-out
//             force (smoothed) has moved by 2 sum_threshold_N from L0, where both models meet
//             (they part by (k - 1)(L - L0): twice the force's error bound for k = 2), the gain
//             is taken when it leaves under half the offset's power (a gain x2 raised on its jump
//             no longer waits for the swing). A step back by about b is no end when the gain led
//             by that bar at the jump (its power before the step) and the leave-one-out force
//             stepped with the reading as the gain implies (dv about dx / k; an end leaves it):
//             a pad that sheds its load L0 within a jump window (a lift-off at 200 Hz) falls by
//             k L0 = L0 + b, and the residual then steps by b as an end's would; the gain is
//             taken on that step instead.
//   negative  a pad only pushes: a loaded pad (leave-one-out force above gain_min_load_N)
//             reading below -airborne_threshold_N for as many ticks as the airborne mean takes
//             is a gain fault with k < 0 (a sign flip) when the least-squares line of the reading
//             on the leave-one-out force v has a slope below 0 by 4 standard errors and the line
//             x = k v through 0 fits better than x = v + b (a negative offset), once v has
//             spanned sum_threshold_N (the bound of its own error) and unless the air has measured
//             the channel's offset already; re-admitted once it reads above +airborne_threshold_N
//             under load for as long.
// Type: invalid > frozen/saturation > noise > spikes > gain > drift > offset (a noise burst
// also trips the spike test). A foot touches down when all its pads come below
// touchdown_height_m. Offset and drift are
// told apart by a line fitted to the fault's direct measurements (airborne means, onset jump;
// and a drift seen to stop in a stance is held as an offset at the level it stopped at, above):
// a drift when, once the swing's air mean has settled (three of its windows), the line's slope
// s stands out of the readings' noise: |s| sqrt(sum (t - mean t)^2) > z sigma_x, z the
// two-sided normal quantile of alpha = T / false_alarm_interval_s (the decision is taken every
// tick, on fits whose ticks are correlated: conservative); until then the type stays (the line
// spans the swings before). A fault the air test raises may have grown through the swings
// before it, under airborne_threshold_N (a slow drift is found one swing after it passes the
// threshold, and that swing alone is too short to show its slope): the air windows of the
// channel's healthy swings since it was last flagged (the last 8) and this swing's are tested
// for a ramp against a step (generic/onset_shape.hpp, at z). Each window is two levels, its
// least-squares line read at mean t -+ D (D^2 = sum (t - mean t)^2 / n), uncorrelated, of
// variance 2 (sigma_x^2 / n + b_q^2), b_q = (q / 2) exp(-2 pi^2 sigma^2 / q^2) the quantiser's
// bias that averaging does not remove (q / 2 without noise): so a step under jump_threshold_N
// inside an earlier window (a mean between two levels, which a ramp would fit) shows as the
// steep slope it is, and fits no ramp. A ramp makes the fault a drift at once, its line fitted
// from the ramp's levels on (each weighted as the readings its variance is worth), when it began
// before this swing (a ramp within this swing's two levels alone is a step inside it as much).
// A pad that swings once in seconds (a quadruped's foot) shows a slow drift in one swing only,
// but the sum residual carried it while the pad was loaded: the corrected residual r is kept as
// block means of ramp_history_s / 16 (16 blocks; not while a substituted pad on the ground takes
// what the total force leaves, which zeroes r), each of variance v (the reference's error over
// a block, correlated over a stride: measured on the second differences d of full blocks with no
// channel flagged, which a constant or a ramp in r leaves untouched, as median(d^2) / (6 x 0.455)
// over the latest 16, which one step does not move; at least 8 of them, else no test). A fault
// the air raises is then a drift at once when those blocks rise along a ramp (onset_shape at z),
// and still do with the air's mean joined to them as one more level (at its mean time, on the
// blocks' healthy level c, variance sigma_x^2 / n + b_q^2: a step inside a block leaves c,
// c + f b, c + b, which a ramp fits exactly for f <= 1/2, but the air then reads c + b, not the ramp's level
// further on) and beating a step inside one block by z^2 as well (onset_shape.hpp's
// step_within_a_point_chi2: a block partway and one or two full ones after it fit a ramp better
// than a plain step), that ramp having begun before this swing and reaching, at the swing's mean time,
// the level the air reads, of its sign and within z sqrt(v + sigma_x^2 / n + b_q^2): one
// channel's fault grew there, not the reference (a reference that drifts while a pad steps ramps
// r to another level); its line is fitted from the ramp's blocks less c, and this swing's
// levels.
// A jump fault whose pad later reads zero in the air is a gain fault (k = 1 + jump / load; k < 0:
// a sign flip; |k| under 0.1: a dead output, frozen and substituted until its reading follows the
// load again); every gain estimate keeps |k| >= 0.1. Tick counters saturate (no overflow).
// Re-admission: when the test that raised the flag has been clear for clear_s (an airborne zero,
// a finite value, varying values, a reverse jump of the estimated size). An airborne zero: the
// swing's mean within airborne_clear_N over three times the air test's readings, or the mean of
// the latest block of the air test's readings (min_airborne_samples) within it (a fault that ends mid-swing by a step under
// jump_threshold_N). A step in flight restarts the air's mean and fit (one line through two
// levels would keep half the fault), and a confirmed jump back in the air re-admits only a
// reading back within airborne_threshold_N of 0 (a fault that changed size is still a fault).
//
// Outputs per channel: fault, fault_type (codes of fault_type.hpp), fault_estimate (measured -
// recovered), recovered (offset/drift: N - b(t), but an offset raised by a jump under load that
// the offset-or-gain test has not decided yet: N / k, k = 1 + b / L0, where that lies nearer v,
// the leave-one-out force, by more than jump_confirm_N (the wrong model is taken only where the
// two lie within about twice v's error of each other; the tests keep judging it as N - b);
// gain: N / k; an unflagged reading on the ground below -airborne_threshold_N, which no pad that
// only pushes reads, v on that tick, and an unflagged airborne one beyond +-airborne_threshold_N,
// 0 (what a pad in the air carries), while they stay unflagged; noise: v + a 10 Hz
// low-pass of
// N - v, v the leave-one-out force, loaded and while no loaded channel is substituted (v carries
// the load's fast moves, which a low-pass of N lags by tens of newtons; the low-pass keeps the
// slow part v misses), else a 10 Hz low-pass of N; spikes: median of the last three readings;
// otherwise (frozen, saturation, invalid: substituted) what the total force leaves once the other
// channels are counted, apportioned among the substituted channels on the ground by least squares
// on the sum and, when `points` gives the soles' layout and two or more are substituted, on the
// plane a rigid sole's loads lie on in full contact (unmeasured_contact_loads.hpp; without it,
// equal shares), each at least 0 and a saturated pad at least its reading, its ceiling; a
// substituted pad on a foot whose readable pads on the ground all read their air level, past its
// landing's touchdown_guard_s (a lifting sole; a landing one may stand on that pad alone), carries
// 0 while another foot not seen so holds a substituted pad too, and else at most what it carried
// on the tick before (a lifting sole takes on no load; the rest stays in the sum residual)),
// virtual (leave-one-out: 0 when airborne, else F_z - sum of the other channels' recovered
// values; NaN while F_z is not finite, the virtual sensor not ready), virtual_ready (1 while F_z
// is finite; while it is not, the sum residual holds and no channel is judged on it).
// `unisolated` is 1 while the low-passed corrected sum residual (the flagged channels taken as
// recovered: what their corrections do not explain) exceeds sum_threshold_N, whether or not some
// channel is flagged, or while the gain test's fit is strong but no channel stands out in it: a
// fault of the virtual sensor's own inputs (IMU), one that cannot be isolated (an offset that
// began inside a touchdown guard), or a correction that no longer fits, reported as such rather
// than blamed on a force sensor. `cannot_judge` (per channel) is 1 for every channel not
// flagged while `unisolated` is: silence there is no verdict of health (the monitor's
// cannot_judge column).
// Feet: as many as `measured` carries channels, `points_per_foot` each (4 pads of a sole, 1 for a
// point foot); `point_height` gives each channel's contact point height above the ground, from
// kinematics (contact_point_height: the pads' heights of 1. below).
// Channel order: the first foot's points, then the next foot's.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "ftsense/calibration.hpp"
#include "ftsense/fault_type.hpp"
#include "ftsense/generic/onset_shape.hpp"
#include "ftsense/generic/spike_episode.hpp"
#include "ftsense/generic/trend_window.hpp"
#include "ftsense/generic/unmeasured_contact_loads.hpp"
#include "ftsense/plugin.hpp"

namespace ftsense::biped {

class ContactForceFdi {
 public:
  static constexpr std::string_view name = "contact_force_fdi";
  static constexpr std::string_view summary =
      "detects, isolates, classifies and recovers contact-point force faults from pad heights, "
      "the total force and signal continuity";
  // For the config reference's port table and the schema (plugin.hpp).
  static constexpr std::string_view example_params =
      R"({"points_per_foot": 4, "noise_std_N": 2.0, "weight_N": 1118.0})";

  // `ftsense calibrate` measures the sensors' white noise and quantisation step on fault-free
  // logs (tick_noise.hpp): one value for all channels, the largest, as every threshold in newtons
  // here follows from them.
  static constexpr auto calibrated_params = std::to_array<CalibratedParam>({
      {"noise_std_N", "measured", FaultFreeStatistic::tick_noise},
      {"resolution_N", "measured", FaultFreeStatistic::resolution},
  });

  struct Params {
    int points_per_foot = 1;
    double noise_std_N = 2.0;
    double weight_N = 0.0;
    double airborne_height_m = 0.005;
    double airborne_settle_s = 0.02;
    double airborne_threshold_N = 0.0;
    double airborne_clear_N = 0.0;
    double jump_threshold_N = 0.0;
    double jump_confirm_N = 0.0;
    double jump_window_s = 0.01;
    double touchdown_guard_s = 0.15;
    double touchdown_height_m = 0.001;
    double resolution_N = 0.0;
    double zero_clamp_N = 0.0;
    double upper_limit_N = 0.0;
    double frozen_min_s = 0.02;
    double false_alarm_interval_s = 86400.0;
    double spike_threshold_N = 0.0;
    double spike_hold_s = 0.8;
    double spike_gap_probability = 0.01;
    double noise_window_s = 0.05;
    double noise_factor = 4.0;
    double sum_cutoff_hz = 1.0;
    double sum_threshold_N = 0.0;
    double clear_s = 0.05;
    double hold_s = 0.2;
    double gain_window_s = 2.0;
    double gain_threshold = 0.2;
    double gain_explained = 0.5;
    double gain_isolation_margin = 0.08;
    double gain_min_load_N = 0.0;
    double follow_ratio = 0.25;
    double ramp_history_s = 8.0;
    std::vector<std::array<double, 2>> points;
    static void describe(ParamSchema<Params>& schema);
  };

  enum Input : std::size_t { kMeasured, kTotalForce, kPointHeight };
  enum Output : std::size_t {
    kFault, kFaultType, kFaultEstimate, kRecovered, kVirtual, kSumResidual, kUnisolated, kVirtualReady, kCannotJudge };

  ContactForceFdi(const Params& params, const StageContext& context);
  [[nodiscard]] const Ports& ports() const noexcept { return ports_; }
  void reset() noexcept;
  void step(const StepIO& io) noexcept;

 private:
  // Least-squares line b(t) = a + s (t - t0) through direct measurements of a channel's fault.
  struct LineFit {
    double n = 0, st = 0, sb = 0, stt = 0, stb = 0, t0 = 0;
    void clear(double origin) noexcept { *this = LineFit{}; t0 = origin; }
    void add(double t, double b, double weight) noexcept;
    [[nodiscard]] double span() const noexcept;
    // sqrt(sum w (t - mean t)^2) [s]: a slope fitted under white noise sigma has standard error
    // sigma / slope_scale().
    [[nodiscard]] double slope_scale() const noexcept;
    void solve(double& a, double& s) const noexcept;
  };

  // Least-squares line x = a + k v of a reading on its leave-one-out force.
  struct SlopeFit {
    double n = 0, sv = 0, sx = 0, svv = 0, sxv = 0, sxx = 0;
    double v_lo = 0, v_hi = 0;
    void add(double v, double x) noexcept {
      v_lo = n > 0 ? std::min(v_lo, v) : v;
      v_hi = n > 0 ? std::max(v_hi, v) : v;
      n += 1; sv += v; sx += x; svv += v * v; sxv += x * v; sxx += x * x;
    }
    // k of x = k v, when the slope is negative beyond 4 standard errors and x = k v fits
    // better than x = v + b (clamped to <= -0.1).
    [[nodiscard]] bool negative_slope(double& k) const noexcept;
  };

  struct Channel {
    // evidence
    double previous = 0.0, previous2 = 0.0;
    // The divisor its reading was taken with in the jump test's sum residual on the last tick on
    // the ground (k for a gain fault, else 1).
    double residual_divisor = 1.0;
    int stale_count = 0;
    double last_stale_value = -1e300;  // the value of the last stuck episode
    int stale_episodes = 0;            // consecutive stuck episodes at that same value
    // The level the reading was last found stuck at under load, a ceiling it may be clipped at
    // again (NaN: none known); kept across episodes until the reading goes above it.
    double ceiling_N = std::numeric_limits<double>::quiet_NaN();
    bool on_ceiling = false;  // healthy, reads that level this tick under load: its load not read
    double max_seen = 0.0;
    // The current spike episode, timed in seconds the spike test could see (not within a
    // touchdown's or the pad's landing guard, where spikes are not looked for).
    generic::SpikeEpisode spikes;
    double last_pad_landing_s = -1e9;  // the pad last took load back from its zero level
    double last_landing_ring_s = -1e9;  // its last change above jump_threshold_N since
    std::vector<double> second_diff;  // ring of |d2|, noise test
    std::vector<double> first_diff;   // ring of |d1| at the same ticks (whiteness)
    std::size_t second_diff_next = 0;
    std::vector<int> noisy_tick;  // ring: 1 where the tick's d2 counts as noisy
    int noisy_count = 0;          // its sum
    int airborne_ticks = 0;
    double airborne_sum = 0.0;
    int airborne_count = 0;
    // The same readings' times u = t - air_origin_s [s]: sum u, sum u^2, sum u x (the window's
    // line, for its two levels); and whether the channel was flagged on any of its ticks.
    double air_origin_s = 0.0;
    double airborne_u_sum = 0.0, airborne_uu_sum = 0.0, airborne_ux_sum = 0.0;
    bool air_window_flagged = false;
    // The air's levels of the swings (windows between steps in flight) the channel spent healthy
    // since it was last flagged: the points before a fault the air test raises, which tell a
    // drift that grew through them from an offset that stepped after them (onset_shape.hpp).
    generic::LevelHistory air_levels;
    // the last jump candidate
    bool jump_pending = false;  // a candidate this tick
    bool jump_member = false;   // in the group awaiting confirmation
    bool relation_pending = false;  // a candidate inside a touchdown guard this tick
    bool relation_member = false;   // in its foot's group awaiting the plane's confirmation
    double relation_jump = 0.0, relation_candidate_load = 0.0;  // this tick's candidate
    double relation_jump_size = 0.0, relation_load_before = 0.0;  // the group's: its jump, the reading before
    double relation_reading_before = 0.0;  // its reading before its foot's group (member or not)
    double jump_size = 0.0;
    double candidate_load = 0.0;
    double jump_load_before = 0.0;
    double onset_load = 0.0;  // L0: the load before the jump that raised the offset (onset_gain)
    bool candidate_flagged = false;      // this tick's candidate jumped while flagged
    // At the jump of its group (the first, not a late one): whether an offset that may yet be a
    // gain had the gain leading the offset-or-gain comparison (gain_leads; the evidence from
    // before the step: the ticks after an offset's end favour the gain's smaller correction), and
    // its leave-one-out force on the tick before.
    bool jump_gain_led = false;
    double jump_virtual_before = 0.0;
    bool jump_from_flagged = false;      // the group's member did (its jump is no onset)
    bool relation_from_flagged = false;  // the plane group's member did
    // A reverse jump of the fault's size inside another foot's touchdown guard: judged by the
    // sum residual's step once the guard is over (end_jump: the step an end implies; end_before: the
    // residual's mean over the jump window before the guard). Likewise a step back while
    // another group is pending, judged a jump window after it by its own step.
    bool end_pending = false;
    // The last tick a drift's reading and its foot's summed reading stepped back by about its
    // size (nearer that than no step; the size beyond the noise of a tick's change, under any
    // jump threshold): a cue for the stance comparison, not a decision [s].
    double stepped_back_s = -std::numeric_limits<double>::infinity();
    bool end_after_guard = false;  // judged after the guard (else: a jump window after the step)
    double end_jump = 0.0, end_before = 0.0, end_since_s = 0.0;
    int end_clear_ticks = 0;  // ticks judged since the guard ended (or since the step)
    std::uint64_t end_group = 0;  // the pending group it was seen beside (not after a guard)
    // A jump inside a touchdown guard that its foot's plane could not judge (the foot not in full
    // contact): judged, as an end is, by the sum residual's step once the guard is over (its
    // jump, the reading before it, the residual's mean before the guard).
    bool onset_after_guard = false;
    double guard_onset_jump = 0.0, guard_onset_load = 0.0, guard_onset_before = 0.0, guard_onset_since_s = 0.0;
    double guard_onset_guard_began_s = 0.0;  // when the guard whose residual it is judged against began
    int guard_onset_plane_group = 0;  // the size of the plane group it was decided in (all members)
    // A healthy channel's step while a group is pending: a member of the late group, decided with
    // it (its jump, the reading before it).
    bool late_candidate = false;  // a candidate this tick
    bool late_member = false;
    double late_jump = 0.0, late_load_before = 0.0;
    bool late_from_flagged = false;  // a flagged member's step back (its end, not an onset)
    // state
    FaultType type = FaultType::none;
    double flagged_since = 0.0;
    double clear_since = -1.0;
    double offset = 0.0, slope = 0.0, gain = 1.0;
    LineFit fit;
    bool fit_has_air = false;
    // A drift raised on a still load from the sum residual's ramp (raise_still_load_fault), its
    // foot not lifted since: its stance began with the reading rising the drift's way, and its
    // plateau is judged from the residual's healthy level it was raised on, against the
    // residual's measured noise, not gain_min_load_N.
    bool still_load_drift = false;
    double still_load_healthy_level = 0.0;  // the sum residual's healthy level it was raised on [N]
    double median_gap = 0.0;  // spiking: reading - median of three on the last tick (jump test's sum)
    // A step in flight while the air fits the fault: the fit starts again on the readings after
    // it (kept until the fit takes its next airborne reading). The air's readings in blocks of min_airborne_samples_: the open block's sum and count,
    // and whether the last whole block's mean read zero (within airborne_clear_N).
    bool air_refit = false, air_block_reads_zero = false;
    double air_block_sum = 0.0;
    int air_block_count = 0;
    // The air's readings start again: its settling, its mean and its blocks (on the ground, a
    // reading without a value, a step in flight).
    void restart_air_readings() noexcept {
      airborne_ticks = airborne_count = 0;
      airborne_sum = airborne_u_sum = airborne_uu_sum = airborne_ux_sum = air_block_sum = 0.0;
      air_window_flagged = false;
      air_block_count = 0;
      air_block_reads_zero = false;
    }
    double recovered = 0.0;
    // The type its recovered value (and so the tick's sum residual) was computed with, stamped
    // after the recovery and the follow test: a test later in the tick may re-type it (an offset
    // taken as a gain), and that tick then belongs to neither correction (gain_regression).
    FaultType recovered_as = FaultType::none;
    double smoothed = 0.0;  // 10 Hz low-pass of the reading (recovery of a noise burst)
    // The last tick a group of its foot's healthy steps, the sum falling, was left unnamed because
    // this pad, at its air level, may have taken their load unread (the unread-load test's evidence).
    double handed_load_s = -1e300;
    double noise_bias = 0.0;  // 10 Hz low-pass of reading - leave-one-out force, while flagged noise
    bool noise_bias_set = false;
    // Does the reading follow the load? Ranges of the smoothed reading and of the leave-one-out
    // force since the channel was raised as offset or drift (or re-typed frozen).
    bool following = false;  // ranges being tracked
    bool frozen_by_follow = false;
    bool follows_load = false;  // offset or drift: its reading has spanned follow_ratio of its load's move
    double loaded_at_s = -1e300;  // the last tick its smoothed reading was above airborne_threshold_N
    double reading_lo = 0.0, reading_hi = 0.0, virtual_lo = 0.0, virtual_hi = 0.0;
    double virtual_smoothed = 0.0;  // the same 10 Hz low-pass as `smoothed`: both lag alike
    FaultType still_window_type = FaultType::none;  // the type the still-reading test last saw
    // Offset or gain? Over the same span, the corrected sum residual's power with the offset's
    // correction and with the gain k = 1 + jump / load that the same onset jump implies.
    double offset_power = 0.0, gain_power = 0.0;
    double load_move_from_onset = 0.0;  // largest |smoothed leave-one-out force - L0| over it
    // A pad that reads below zero under load (sign flip): the run, its regression on the load.
    double last_virtual = 0.0;  // the leave-one-out force of the previous tick
    int negative_ticks = 0, positive_ticks = 0;
    SlopeFit negative_fit;
    // While held as a gain (not a sign flip): the reading on its leave-one-out force, x = k v,
    // over loaded ground ticks outside touchdown guards while it is the one channel flagged
    // (refit_gain).
    SlopeFit gain_fit;
    bool sign_fault = false;
    // An offset that may be a gain (offset_may_be_gain) last read, above its air level, nearer its
    // leave-one-out force as x / k than as x - b (by jump_confirm_N): the recovery's choice.
    bool reads_as_gain = false;
  };

  void raise(Channel& c, FaultType type, double t) noexcept;
  // The stance-regression gain test (see the header comment); runs after recovery.
  void gain_regression(std::span<const double> measured, std::span<const double> recovered,
                       std::span<const double> height, double residual,
                       bool usable, double t) noexcept;
  void restart_gain_window() noexcept;
  // A touchdown guard's tick (the regression's usable ticks but for the guard): a held gain's
  // comparison of its two explanations over the guard (guard_powers_), judged after it.
  void compare_held_gain_in_guard(std::span<const double> measured, std::span<const double> recovered,
                                  std::span<const double> height, double residual, double t) noexcept;
  // The gain window's verdicts once it is full: re-admissions, then a new or refined gain.
  void judge_gain_window(double t) noexcept;
  // A new gain from the window since an unexplained residual's onset (since_unexplained_).
  void judge_since_unexplained(double t) noexcept;
  // A drift that has stopped, its reading `level` [N] off its load: held as an offset there.
  void hold_as_offset(Channel& c, double level) noexcept;
  // How far off its load [N] a drift's flat reading over `ticks` must sit to be held as a plateau
  // (gain_min_load_N; for a still-load drift, z of the residual's measured noise if that is less).
  [[nodiscard]] double plateau_bar(const Channel& c, int ticks) const noexcept;
  // The variance v of a full block of the sum residual: the median of the latest second
  // differences d^2 over 6 x 0.455 (d ~ N(0, 6 v)); unknown from fewer than 8.
  [[nodiscard]] std::optional<double> sum_block_variance() const noexcept;
  // A new flag of the gain test whose implied load did not move: held as a drift when the sum
  // residual's blocks since the last flag change rose along a ramp, else as an offset of their step.
  void raise_still_load_fault(Channel& c, double implied_load, double t) noexcept;
  void clear(Channel& c) noexcept;
  // What the evidence loop leaves for the rest of the tick: whether any foot is within its
  // touchdown guard, the jump test's candidates (a new group's and a late one's, with their summed
  // steps), the readings' sum as the jump test's residual takes it (raw_sum, and the last tick's
  // correction for a spiking median's lag), and the tick's flags.
  struct TickEvidence {
    bool touching_down = false;
    int jump_candidates = 0;
    bool group_emptied = false;  // every member of the pending group was a one-tick spike
    bool any_step = false;       // a channel stepped (the still-reading test's window restarts)
    double jump_sum = 0.0;
    int late_candidates = 0;  // healthy channels stepping while a group is pending
    double late_jump_sum = 0.0;
    double raw_sum = 0.0;
    double median_lag_correction = 0.0;
    bool all_finite_readings = true;  // every channel has a value
    bool divisor_changed = false;     // a gain's correction changed on a loaded pad
  };
  // The evidence, channel by channel (contact_force_fdi_evidence.cpp): the feet's touchdowns and
  // summed readings, then each channel's jump, repeat, spike, noise, air and sign evidence. Most
  // decisions come later; a missing value (invalid), a one-tick spike leaving its group and a
  // fault's step back (its end's judgment opened) are settled here.
  TickEvidence observe_evidence(std::span<const double> measured, std::span<const double> height, bool fz_ok,
                                int ticks_since_start, double t) noexcept;
  // The jump groups' verdicts of this tick: the first group's and the late one's, each decided
  // (its window complete) and confirmed (the residual stepped by its sum).
  struct GroupDecisions {
    bool decided = false, confirmed = false, late_decided = false, late_confirmed = false;
    // A loaded channel is flagged as anything but a corrected fault: its reading is not its load,
    // so the gain tests take no evidence from this tick. Judged on the flags as they stood before
    // this tick's decisions (decide_channels), read after them.
    bool uncorrected_loaded = false;
  };
  // The jump test's groups (contact_force_fdi_jump_groups.cpp): the sum residual's history, a
  // new group formed from this tick's candidates, a pending one confirmed or dropped once its
  // window is complete, ends and onsets seen inside a touchdown guard judged after it, and the
  // feet's plane verdicts.
  GroupDecisions judge_jump_groups(std::span<const double> measured, std::span<const double> height, double fz,
                                   const TickEvidence& ev, double t) noexcept;
  // The evidence loop's tests decided, channel by channel (contact_force_fdi_channel_decisions.cpp);
  // the tests that need this tick's corrected sum residual run later in `step`.
  void decide_channels(std::span<const double> measured, std::span<const double> height,
                       const GroupDecisions& groups, bool touching_down, double t) noexcept;
  // Each channel's recovered value before the virtual sensor (contact_force_fdi_recovery.cpp):
  // corrected from its own reading, or substituted from what the total force fz leaves (NaN fz:
  // none substituted). Returns the sum of the values not substituted; unknown_loaded counts the
  // loaded channels that had to be.
  double recover(std::span<const double> measured, std::span<const double> height, double fz, double t,
                 std::span<double> recovered, int& unknown_loaded) noexcept;
  // The still-reading test (header comment), once the corrected sum residual of this tick is known.
  void still_reading_test(std::span<const double> measured, std::span<const double> height, double residual,
                          bool usable, bool stepped, double t) noexcept;
  // The unread-load test (header comment), after the still-reading test has smoothed this tick's
  // residual.
  void unread_load_test(std::span<const double> height, bool usable, double t) noexcept;
  // Pad c (reading x, at `height`) takes its load back on this tick, on the ground: from its zero
  // level, while the others left it none, to beyond airborne_threshold_N (its own landing). "None":
  // its leave-one-out force within airborne_threshold_N; or, for a healthy pad that read its zero
  // level on the two ticks before, within the total force's error and a driver's zero clamp
  // (zero_evidence_above_N_, "unloaded" as the frozen test takes it: a 180 kg biped's leave-one-out
  // force strays by 15 N where its 2 N sensors' 4 sigma is 8 N). Not so for a flagged pad, whose steps
  // are the evidence of its fault's end (a drift's end on a loading pad was held 1.2 s with the
  // wider bar), nor for one tick at the zero level (a loaded pad's downward spike clipped at a
  // driver's zero clamp: a contact's bounce inside the guard is ring_step's). (Run for every
  // channel on every tick: the rarest conditions first.)
  [[nodiscard]] bool pad_lands(const Channel& c, double x, double height) const noexcept {
    return std::abs(c.previous) <= params_.airborne_threshold_N && x > params_.airborne_threshold_N &&
           !(height > params_.airborne_height_m) && std::isfinite(c.last_virtual) &&
           (c.last_virtual < params_.airborne_threshold_N ||
            (c.type == FaultType::none && c.last_virtual < zero_evidence_above_N_ &&
             std::abs(c.previous2) <= params_.airborne_threshold_N));
  }
  // Pad c, on the ground, rings after its landing (as the jump test judged it until the tick
  // before, or its contact is lost or made again: contact_step) and jumps by jump_threshold_N on
  // this tick.
  [[nodiscard]] bool ring_step(const Channel& c, double x, double height, double t) const noexcept {
    return t - c.last_pad_landing_s < params_.touchdown_guard_s && std::abs(x - c.previous) > params_.jump_threshold_N &&
           (t - c.last_landing_ring_s < params_.jump_window_s || contact_step(c, x)) &&
           !(height > params_.airborne_height_m);
  }
  // Reading x steps to or from pad c's air level: inside its landing's guard, its contact lost or
  // made again, however long after the last ring (a 180 kg biped's heel bounces off the ground
  // for a tick 8-10 ms apart, a jump window or more), not a sensor's jump or spike.
  [[nodiscard]] bool contact_step(const Channel& c, double x) const noexcept {
    return std::abs(x) <= params_.airborne_threshold_N || std::abs(c.previous) <= params_.airborne_threshold_N;
  }
  // This tick's jump candidates (net step jump_sum in the residual's terms) may be load handed to
  // a pad of their loaded foot that does not read it: a healthy pad on the ground at its air
  // level, unloaded since its foot landed (or, against two or more healthy candidates of its foot,
  // any such pad at its air level), while the sum falls (its landing, unread); a stuck
  // reading (frozen, saturated, not named) while the sum falls or while it carries load; an
  // offset the air test measured not yet seen to follow its load; against two or more healthy
  // candidates of its foot, a held gain among them stepping from its air level (it may have ended
  // in the air; its correction's error is then the group's step). Then no verdict from the jump.
  // Marks the pads such a group of two or more healthy steps may have handed load (handed_load_s).
  [[nodiscard]] bool unread_landing_may_explain(std::span<const double> height, double jump_sum) noexcept;
  // Pad c, not a jump candidate, on the ground of a loaded foot f, may take or give load unread
  // (unread_landing_may_explain's three cases; `fell`: the sum's step is down; `several_onsets`:
  // two or more of the foot's candidates are healthy).
  [[nodiscard]] bool may_hold_unread_load(const Channel& c, std::size_t f, bool fell,
                                          bool several_onsets) const noexcept;
  // A gain's reading x back at its air level (within airborne_threshold_N of 0): a step that took
  // it there is its load leaving (a scaled zero reads zero), no sign that the gain ended. Also an
  // offset that may yet be a gain (offset_may_be_gain) and read as one before the step
  // (reads_as_gain): the air test tells them. One that read as x - b (an offset b on an unloaded
  // pad reads b, a gain reads 0) ended with that step.
  [[nodiscard]] bool gain_reads_air_level(const Channel& c, double x) const noexcept {
    return (c.type == FaultType::gain || (c.reads_as_gain && offset_may_be_gain(c))) &&
           std::abs(x) <= params_.airborne_threshold_N;
  }
  // A gain's k refitted on its own evidence: its reading against its leave-one-out force, which
  // no other channel's fit shares (the sum residual's fit often cannot isolate a pad of a sole
  // loaded with its neighbours, so it cannot refine k either). Only while no other channel is
  // flagged: with a second fault in the sum, the leave-one-out force carries it, and a fit to it
  // would make a wrongly held gain absorb that fault (other draw walk 6, in a try: two healthy
  // pads held as gains 1 s longer). Taken when the fit spans
  // sum_threshold_N of load over stance_min_ticks_ and its k differs from the one held by
  // relation_z_ standard errors and by half gain_threshold.
  void refit_gain(Channel& c) noexcept;
  // Raises a reading the sum residual shows stuck (still or unread) as frozen; the follow test
  // re-admits it when its reading follows the load again.
  void raise_stuck(Channel& c, double t) noexcept;
  // The air's window of readings closes (the pad lands or steps in flight): a channel healthy
  // on all its ticks keeps its levels among its air_levels.
  void close_air_window(Channel& c) noexcept;
  // The air's window so far as levels: its least-squares line a + s (t - mean t) read at
  // mean t -+ D, D^2 = sum (t - mean t)^2 / n, two uncorrelated levels of variance 2 sigma^2 / n
  // each that carry the window's mean and its slope (one level, its mean, when its times do not
  // spread), plus the quantiser's bias squared; without the reading drop_reading at drop_time
  // unless that is NaN. Writes them to `out` (room for 2); returns how many (0: too few readings).
  std::size_t air_levels_of_window(const Channel& c, double drop_reading, double drop_time,
                                   std::span<generic::LevelPoint> out) const noexcept;
  // Raised by the air test (an offset so far): a drift instead when the levels of its healthy
  // swings before, with this one, rise along a ramp the step does not explain (onset_shape.hpp);
  // the air's fit then starts from the ramp's swings, x the tick's reading (added after).
  void type_air_onset(Channel& c, double x, double t) noexcept;
  // Raised by the air test and still an offset: a drift instead when the corrected sum residual's
  // block means (sum_levels_), and the air's mean after them, rose along a ramp that began before
  // this swing and reaches, by this swing, the level the air reads (each within z of their noise):
  // one channel's fault grew there while its pad was loaded. The air's fit then starts from the ramp's blocks before this swing
  // (less the residual's healthy level) and this swing's levels, x the tick's reading.
  void type_sum_onset(Channel& c, double x, double t) noexcept;
  // Types the channel a drift from t and starts its air fit from levels of its fault: `history`
  // less healthy_level, then this swing's own (each weighted as the readings its variance is worth).
  void start_drift_from_levels(Channel& c, double t, std::span<const generic::LevelPoint> history,
                               double healthy_level, std::span<const generic::LevelPoint> swing) noexcept;
  // Closes or extends the sum residual's block with this tick's residual (usable: F_z and every
  // reading finite; clean: no channel flagged).
  void observe_sum_block(double residual, bool usable, bool clean, double t) noexcept;
  // The bar a landing's residual step must clear: z_g times the RMS of the healthy landings' steps,
  // at least floor_N.
  [[nodiscard]] double landing_step_bar(double floor_N) const noexcept;
  // Raises a confirmed onset jump as an offset of its size (the load before it kept for onset_gain).
  void raise_jump_onset(Channel& c, double jump, double load_before, double t) noexcept;
  // The follow test (header comment), after the leave-one-out force of this tick is known.
  void follow_test(Channel& c, double reading, double virtual_force, double t) noexcept;
  // The offset-or-gain test (header comment), once the corrected sum residual of this tick is known.
  void offset_or_gain_test(Channel& c, double reading, bool airborne, double residual) noexcept;
  // The gain k = 1 + b / L0 that a jump b raised on a loaded pad (load L0 > gain_min_load_N before
  // it) implies; none when the pad was not loaded or the jump is under a tenth of its load.
  [[nodiscard]] std::optional<double> onset_gain(const Channel& c) const noexcept;
  // An offset raised by a jump under load, not yet seen in the air, whose onset implies a gain of
  // at least kMinGain: it may yet be that gain, whose error (k - 1) L moves with its load.
  [[nodiscard]] bool offset_may_be_gain(const Channel& c) const noexcept;
  // Such an offset whose gain leads the offset-or-gain comparison by its bar (under half the
  // offset's residual power since the span began), whether or not the load has yet moved enough
  // for that test to decide.
  [[nodiscard]] bool gain_leads(const Channel& c) const noexcept;
  // A first group member's step back, decided this tick: is it such an offset's gain shedding
  // (or taking) load (the offset, or the gain it was taken for since the jump, with its k)? The
  // gain led at the jump, and the leave-one-out force stepped across it as
  // the gain implies for the reading's step (both to last tick: x / k, within residual_steps_by's
  // band), where an offset's end leaves that force where it was.
  [[nodiscard]] bool step_is_gains_load(const Channel& c, double load_before) const noexcept;
  void take_gain(Channel& c, double k) noexcept;
  // An offset's or drift's size at time t, b + s (t - t0).
  [[nodiscard]] static double fault_at(const Channel& c, double t) noexcept { return c.offset + c.slope * (t - c.fit.t0); }
  // The feet's plane relations this tick: their window steps, their fault-free statistics and the
  // groups of jumps inside a touchdown guard they confirm (after the channel tests).
  void relation_jumps(std::span<const double> measured, std::span<const double> height, double t) noexcept;
  // Channel j's reading is not its load, as flagged until this tick: substituted from the total
  // force on the ground, or a noise burst (anywhere: its noise is in its foot's summed reading).
  [[nodiscard]] bool unread(std::size_t j, std::span<const double> height) const noexcept;
  // Load rocked between pad j (a one-tick excursion `spike` [N]) and another pad of its foot.
  [[nodiscard]] bool load_rocked(std::size_t j, double spike, std::span<const double> measured) const noexcept;
  // Foot f touched down within touchdown_guard_s of t (its landing's transient; its pads taking
  // their loads one by one).
  [[nodiscard]] bool foot_landing(std::size_t f, double t) const noexcept {
    return t - last_touchdown_s_[f] < params_.touchdown_guard_s;
  }
  // The fault's size now (a gain's from the reading before the step, `load_before`).
  [[nodiscard]] static double fault_size(const Channel& c, double t, double load_before) noexcept;
  // A one-tick change that takes a fault of that size back: |jump + size| < 0.4 |size| + jump_confirm_N.
  [[nodiscard]] bool steps_back(double jump, double size) const noexcept;
  // The sum residual stepped by about `expected` over a jump window (within max(jump_confirm_N,
  // 50 %), same sign), and by confirm_N or more: how a group or a fault's end is confirmed.
  [[nodiscard]] bool residual_steps_by(double step, double expected, double confirm_N) const noexcept;
  // The sum residual's mean over a jump window: the ring's newest jump_window_ticks_, after
  // skipping the newest `skip` (at most jump_window_ticks_: the ring holds two windows).
  [[nodiscard]] double recent_residual_mean(std::size_t skip = 0) const noexcept;
  // A foot's decided group: its relations stepped by what its jumps imply, beyond their noise, and
  // not by what a pad whose offset may be a gain (offset_may_be_gain) does as its load moves: read
  // through x / k, its reading's change since the group began would move the plane by
  // w (1 - 1/k) of it less; where that leaves the plane's step within its noise, the step is that
  // pad's load moving (a landing handing load over), not a sensor's step.
  [[nodiscard]] bool relation_confirmed(std::size_t foot, std::span<const double> measured, double t) const noexcept;

  Ports ports_;
  Params params_;
  double period_s_;
  std::size_t feet_points_;
  std::size_t feet_ = 2;
  std::vector<Channel> channels_;
  std::vector<std::size_t> channel_foot_;  // per channel j: its foot, j / feet_points_ (divided once)
  std::vector<double> residual_ring_;  // sum residual history, 2 * jump window
  std::size_t residual_next_ = 0;
  std::size_t residual_count_ = 0;
  double sum_filtered_ = 0.0;
  // The still-reading test: the corrected sum residual low-passed as the readings' `smoothed`, and
  // its windows (each shared by every channel: one residual move, judged against every still
  // reading). The long one opens once the smoothers have settled and lasts until judged; the
  // short ones open in turn every half settling, each replacing the oldest (so each lives two
  // settlings): one begins within half a settling after any onset, free of the motion the stuck
  // reading made before it stuck, which keeps the long window from naming it.
  struct StillWindow {
    bool active = false;
    double start_s = 0.0;  // a window opened on this tick (start_s == t) is judged from the next
    double residual_lo = 0.0, residual_hi = 0.0;
  };
  static constexpr std::size_t kShortStillWindows = 4;
  static constexpr std::size_t kLongStillWindow = kShortStillWindows;  // the last slot
  double residual_smoothed_ = 0.0;
  bool residual_smoothed_started_ = false;
  std::array<StillWindow, kShortStillWindows + 1> still_windows_{};
  // Per window and channel (window after window): the smoothed reading's range, and whether the
  // channel was on the ground and not flagged throughout.
  std::vector<double> still_lo_, still_hi_;
  std::vector<char> still_grounded_;
  // ... and the smoothed reading's range since the residual was last within residual_near_N_ of
  // its window's low, and of its high (short windows).
  std::vector<double> since_low_min_, since_low_max_, since_high_min_, since_high_max_;
  std::vector<double> smoothed_;  // this tick's smoothed readings, gathered (work space)
  std::vector<char> judgeable_;   // this tick: on the ground, not flagged, read (work space)
  std::size_t next_short_window_ = 0;  // the slot the next short window takes
  double next_short_window_s_ = -1e300;
  double short_window_stagger_s_ = 0.0;
  // What a stuck reading's smoothed value spans: its noise, +-4 sigma after the low-pass, and a
  // quantisation level [N].
  double still_band_N_ = 0.0;
  double quantiser_bias_N_ = 0.0;  // the most a mean of readings stays off by quantisation (air_levels_of_window)
  // The corrected sum residual's recent history (type_sum_onset): block means of
  // ramp_history_s / LevelHistory::kCapacity each (their variance kept relative to a full
  // block's), and the latest squared second differences of full blocks in which no channel was
  // flagged (their median: 6 x 0.455 times a block mean's variance).
  generic::LevelHistory sum_levels_;
  int sum_block_target_ticks_ = 500;
  int sum_block_ticks_ = 0;   // ticks into the open block
  int sum_block_count_ = 0;   // its usable ticks
  double sum_block_sum_ = 0.0, sum_block_t_sum_ = 0.0;
  bool sum_block_clean_ = true;  // no channel flagged on any of its ticks
  int sum_block_full_run_ = 0;  // full clean blocks in a row, at most 2
  std::array<double, 2> sum_block_last_means_{};  // the two blocks before, oldest first
  std::array<double, generic::LevelHistory::kCapacity> sum_block_d2_{};
  std::size_t sum_block_d2_next_ = 0, sum_block_d2_count_ = 0;
  double residual_near_N_ = 0.0;  // follow_ratio x sum_threshold_N: a residual move smaller is no move
  double still_window_settle_until_s_ = -1e300;
  // Per foot, for the substituted loads' split: its readable pads on the ground all read their
  // air level (a lifting sole).
  std::vector<char> foot_reads_unloaded_;
  // The unread-load test: its one candidate (channels_.size() or more: none) and since when.
  std::size_t unread_candidate_ = static_cast<std::size_t>(-1);
  double unread_since_s_ = 0.0;
  double residual_within_bound_s_ = -1e300;  // the last tick its smoothed residual was within sum_threshold_N
  bool started_ = false;
  int guard_onsets_clear_ticks_ = 0;  // ticks judged since the last guard (or candidate) ended
  // The sum residual's step across a healthy touchdown guard (its mean a jump window after the
  // guard less its mean before): its sum of squares and count, learnt as the walk goes, and the
  // ticks since the last guard ended (-1: measured, or no guard yet). Judged from five landings
  // on (an RMS within about 30 %, chi-square with 5 degrees of freedom), against guard_z_ times
  // it: the two-sided normal quantile of alpha = touchdown_guard_s / false_alarm_interval_s, one
  // decision per landing (landings are at least a guard apart).
  static constexpr int kMinGuardSteps = 5;
  int guard_step_ticks_ = -1;
  double guard_step_square_ = 0.0;
  double guard_z_ = 5.0;
  int guard_step_count_ = 0;
  double guard_began_s_ = -1e300;       // when the current (or last) touchdown guard began
  double last_flag_change_s_ = -1e300;  // the last tick a channel was raised or re-admitted
  double last_tick_s_ = -1e300;         // this tick's time (clear() has no time of its own)
  double residual_before_touchdown_ = 0.0;  // its mean over the jump window before the guard
  bool residual_before_known_ = false;     // the ring held a whole window then
  bool was_touching_down_ = false;
  bool group_pending_ = false;
  std::uint64_t group_serial_ = 0;  // counts the groups formed
  double group_before_ = 0.0;       // the residual's mean over the jump window before the group's jump  // jump candidates of one tick, awaiting confirmation
  int group_age_ = 0;
  double group_sum_ = 0.0;
  int group_size_ = 0;
  // The late group: healthy channels' steps on one tick while the group above was pending (at most
  // one). Both are decided together, a jump window after the late group's jump, by which of the
  // two sums the residual's step from before the first group's jump matches best.
  bool late_pending_ = false;
  bool group_deferred_ = false;  // the first group's window is over; decided with the late group
  // Ticks since a loaded channel's gain correction in the jump test's residual was set, changed
  // or dropped (capped): a group's two windows must not straddle it.
  int ticks_since_divisor_change_ = 1'000'000'000;
  // The last tick a healthy channel read its ceiling under load (Channel::on_ceiling), and ticks since.
  double ceiling_read_s_ = -1e300;
  int ticks_since_ceiling_ = 1'000'000'000;
  int late_age_ = 0;
  double late_sum_ = 0.0;
  int late_size_ = 0;
  // Per foot.
  std::vector<double> last_touchdown_s_;
  std::vector<char> foot_airborne_;
  std::vector<std::array<double, 2>> foot_sum_;  // summed reading one and two ticks ago
  std::vector<int> foot_sum_ticks_;              // consecutive ticks with every pad's value, up to 2
  std::vector<double> foot_d2_;                  // second difference of the summed reading, this tick
  std::vector<int> foot_unread_;                 // its pads whose reading is not their load (unread())
  std::vector<int> foot_landing_pads_;           // its pads that land or ring-step on this tick
  // Per channel, this tick: its own landing's step (before the jump test's state moves on).
  static constexpr char kNoLandingStep = 0, kRingStep = 1, kLands = 2;
  std::vector<char> landing_state_;
  double start_time_s_ = 0.0;
  int noise_window_ticks_;
  int frozen_ticks_ = 2;        // n_f, the frozen test's run length (INT_MAX: never reached)
  bool repeat_test_off_ = false;  // no bounded n_f: the quantiser is coarser than the noise dithers
  double repeat_band_N_ = 0.0;  // q / 2
  double tick_noise_N_ = 0.0;   // the noise test's bar on a pad's second difference: sqrt(6 (sigma^2 + (q/2)^2)) x noise_factor
  double foot_noise_N_ = 0.0;   // ... and on its foot's summed reading's: tick_noise_N_ sqrt(points_per_foot)
  double zero_evidence_above_N_ = 0.0;  // a zero reading is frozen evidence above this load
  int jump_window_ticks_;
  int min_airborne_samples_ = 10;
  static constexpr double kSmoothingHz = 10.0;  // cutoff of `smoothed` and `virtual_smoothed`
  double smoothing_ = 1.0;  // gain of that low-pass per tick
  double sum_gain_ = 1.0;   // gain per tick of the sum residual's low-pass (sum_cutoff_hz)
  double smoother_settle_s_ = 0.0;  // its settling time (five time constants)
  // How long an end or onset seen inside a guard may wait for its judgment (the guards keep coming).
  double guard_pending_limit_s_ = 0.0;
  generic::SpikeHoldRule spike_rule_;  // spike_hold_s, min(clear_s, spike_hold_s), ln(1 / spike_gap_probability)
  // Gain test: the fit r ~ b + beta_j N^_j of the corrected sum residual r on every channel's
  // recovered reading N^_j, exponentially weighted over a window (forgetting factor f per usable
  // tick): <N^_j, N^_j>, <N^_j, r>, sum N^_j per channel, sum r, <r, r> and the weight sum f^i.
  struct GainWindow {
    // The fit within each stance of channel j's point, weighted alike: the current stance's
    // weight and sums of N^_j, r, N^_j^2, N^_j r, and the centred sums of closed stances;
    // whether a stance of its point closed within the window, and the weight of its ticks in the
    // air since (a gain reads 0 there, as its load does: the line through the origin needs those
    // ticks as well). A tick of unknown height (NaN) is in no stance and in no air: it splits no
    // stance and is no evidence of an unloaded pad (the window-wide sums take it all the same).
    struct StanceSums {
      double w = 0.0, x = 0.0, r = 0.0, xx = 0.0, xr = 0.0;
      double closed_xx = 0.0, closed_xr = 0.0;
      bool stance_closed = false;
      double air_after_stance = 0.0;
    };
    std::vector<double> xx, xr, x;
    std::vector<StanceSums> stance;
    double r = 0.0, rr = 0.0, weight = 0.0;
    int ticks = 0;  // usable ticks since the window last restarted (saturating by whole windows of 10)
    void resize(std::size_t channels);
    void restart() noexcept;
    // One usable tick; false when <r, r> has grown too large to hold (start again, not stay blind).
    bool add(std::span<const double> recovered, std::span<const double> height, double airborne_height_m,
             double residual, double f) noexcept;
  };
  // A window's best fit among the channels not flagged or held as gains that carried load
  // (<N^_j, N^_j> at least min_power): the share of r's variation it explains
  // (cov^2 / (var N^ var r)), the best share of any other channel (those under min_power too),
  // its slope and the centred sums it came from. best == channels when no channel carried load.
  // With only_gains_from_the_air, a channel whose fit is no gain begun in the air
  // (fits_a_gain_from_the_air) is never the best, and its share counts among the others'.
  struct GainFit {
    std::size_t best;
    double explained = 0.0, second_explained = 0.0, beta = 0.0;
    double x_variation = 0.0, covariation = 0.0, r_variation = 0.0;
  };
  [[nodiscard]] GainFit best_gain_fit(const GainWindow& w, double min_power,
                                      bool only_gains_from_the_air = false) const noexcept;
  // Channel j's fit r = b + slope N^_j in `w` is one of a gain begun in the air: slope < 1 (or the
  // reading negative on the whole) and |b| <= sum_threshold_N.
  [[nodiscard]] bool fits_a_gain_from_the_air(const GainWindow& w, std::size_t j, double slope) const noexcept;
  // A new gain's confirmation within the stances of `w` (see gain_regression): beta of the fit's
  // sign and beyond `threshold` there too.
  [[nodiscard]] static bool stances_confirm(const GainWindow& w, const GainFit& fit, double threshold) noexcept;
  // How many corrections (offset, drift, gain) the sum residual carries: those of pads on the
  // ground (heights unknown, NaN, count as on the ground). A corrected pad in the air is
  // recovered as 0, what it carries there, whatever its correction.
  [[nodiscard]] int corrections_in_residual(std::span<const double> height) const noexcept;
  GainWindow gain_window_;
  // The same fit from where the corrected sum residual left its bound with no channel flagged
  // (`unisolated`; open through its returns within the bound): a gain that begins in the air lands reading k times its load with no jump, and
  // the gain window then holds the stances before it, on which its pad's fit is flat. Kept beside
  // gain_window_ (which judges as before), for 3 gain windows at most, closed by any flag.
  GainWindow since_unexplained_;
  bool since_unexplained_open_ = false;
  // Per channel held as a gain fault, since its correction was last set: ticks, <r_raw, r_raw>
  // with r_raw = r + N_j - N^_j (the reading taken as it is) and <r, r>.
  std::vector<int> gain_held_ticks_;
  std::vector<double> gain_raw_rr_;
  std::vector<double> gain_held_rr_;
  // The same for every channel held as a gain together, while two or more are and the set has
  // not changed: r_joint = r + sum over them of (N_j - N^_j); which channels the sums are for.
  std::vector<char> joint_gain_set_;
  int joint_gain_ticks_ = 0;
  double joint_raw_rr_ = 0.0, joint_held_rr_ = 0.0;
  // The margin by which the reading as it is must beat a correction to drop it: the correction
  // leaves this many times its residual power (twice its RMS).
  static constexpr double kReadingWinsPowerRatio = 4.0;
  // The same powers summed (not weighted) over usable ticks on the ground while held as a gain, an
  // offset or a drift, for a correction gone wrong in a stance: <r_raw, r_raw>, <r, r>, the correction's
  // own power <N_j - N^_j, N_j - N^_j>, and, for an offset raised by a jump under load and not
  // yet measured in the air, <r_gain, r_gain> with the reading taken as the gain that same onset
  // implies (r_gain = r - N^_j + N_j / k; it may yet be a gain, whose error shrinks as its pad
  // unloads, as an ended offset's would seem to).
  struct StancePowers {
    FaultType type = FaultType::none;  // the fault the sums were taken for
    int ticks = 0;
    double raw_rr = 0.0, held_rr = 0.0, correction_cc = 0.0, gain_rr = 0.0, gain_cc = 0.0;
    bool gain_model = false;  // some tick had the gain explanation
    // As constructed for `t`: every sum grows only through add (which counts a tick) or
    // add_gain_model (which sets gain_model), so these three say it.
    [[nodiscard]] bool fresh_for(FaultType t) const noexcept { return ticks == 0 && !gain_model && type == t; }
    // r_raw over the present trend window (for a drift's end or its plateau, below), on the
    // ticks' times (generic::TrendWindow): a drift grows with time, and the usable ticks the
    // window takes need not be consecutive (a substituted loaded pad or a landing elsewhere leaves
    // gaps; counted by usable ticks, a stance before a gap of seconds and one after it were glued
    // into one line).
    generic::TrendWindow trend_window{};
    void add(double raw, double held, double correction, double t_s, double period_s) noexcept {
      raw_rr += raw * raw;
      held_rr += held * held;
      correction_cc += correction * correction;
      ticks = ticks < std::numeric_limits<int>::max() ? ticks + 1 : ticks;
      trend_window.add(raw, t_s, period_s);
    }
    // The last window closed as sloped rose the way the drift does (a plateau's flat window
    // follows the drift going on; a fade's follows its fall).
    bool rose_with_drift = false;
    // For a drift that ended at once: the sum residual's level (the readings as the jump test
    // takes them, this one as it is) over the usable ticks before the sums' first, that level's
    // variance in units of the residual's, the correction on that first tick, and the residual's
    // sum over these ticks. The level is NaN if any of these holds: the reading itself did not
    // step back by about the correction within a jump window before that first tick; the level
    // had not settled (fewer than 2 clear_s of usable ticks in a row); a window of these sums
    // was found sloped (whatever stepped, the reading has moved since).
    double level_before = std::numeric_limits<double>::quiet_NaN();
    double level_variance = 1.0;
    double correction_before = 0.0;
    double level_sum = 0.0;
    // The gain explanation's residual and its own correction N_j - N_j / k.
    void add_gain_model(double as_gain, double correction) noexcept {
      gain_rr += as_gain * as_gain;
      gain_cc += correction * correction;
      gain_model = true;
    }
    // The reading as it is leaves a quarter of the residual power of every other explanation.
    [[nodiscard]] bool reading_leads() const noexcept {
      return held_rr > kReadingWinsPowerRatio * raw_rr && (!gain_model || gain_rr > kReadingWinsPowerRatio * raw_rr);
    }
    // ... over at least min_ticks, and each other explanation moved the reading by sqrt(bound_sq)
    // RMS or more (one that moved it less is within what the residual's error can mimic: a gain
    // on a pad that has unloaded reads as its load does).
    [[nodiscard]] bool reading_wins(int min_ticks, double bound_sq) const noexcept {
      const double bound = static_cast<double>(ticks) * bound_sq;
      return ticks >= min_ticks && reading_leads() && correction_cc >= bound && (!gain_model || gain_cc >= bound);
    }
    // A drift's end: does the reading as it is stay flat where the drift, had it gone on, would
    // have shown? Over the trend window, r_raw's slope c_1 and bend c_2 with their standard errors
    // (generic::TrendWindow). Undecided while z se_1 is more than a quarter of the fitted
    // drift's slope per tick (the window could not yet show a drift going on at a quarter of its
    // fitted rate); then flat when neither the slope c_1 nor the bend c_2 is beyond z of its
    // standard error, else sloped (a bend: the reading fell and rose again within the window,
    // which a line through it would call flat).
    enum class Trend { undecided, flat, sloped };
    [[nodiscard]] Trend trend(double drift_per_tick, double z) const noexcept {
      if (trend_window.count() < 4) return Trend::undecided;
      const generic::TrendWindow::Fit fit = trend_window.fit();
      if (!(z * fit.se1 <= 0.25 * std::abs(drift_per_tick))) return Trend::undecided;
      return fit.flat(z) ? Trend::flat : Trend::sloped;
    }
    // A drift that ended at once: the residual stepped from its level before these sums by minus
    // the correction c then, nearer that than no step (a fade moves it by its rate), with c / 2,
    // that midpoint's distance from each, beyond z of the step's standard error (r_raw's scatter
    // s about its line and bend, through the level's variance and the mean over these n ticks:
    // s sqrt(level_variance + 1 / n)); and the window is flat at whatever precision it has (no
    // slope, no bend beyond z of their standard errors): it need not be long enough to show the
    // drift going on, since a step, not a fade, brought the reading to the load.
    [[nodiscard]] bool stepped_back(double z) const noexcept {
      if (!std::isfinite(level_before) || trend_window.count() != ticks || ticks < 4) return false;
      const double n = static_cast<double>(ticks);
      const double step = level_sum / n - level_before;
      if (!(std::abs(step + correction_before) < 0.5 * std::abs(correction_before))) return false;
      const generic::TrendWindow::Fit fit = trend_window.fit();
      const double se = fit.s * std::sqrt(level_variance + 1.0 / n);
      return 0.5 * std::abs(correction_before) >= z * se && fit.flat(z);
    }
  };
  // Over the present stance of the channel's point, and (an offset) since the CUSUM of the
  // reading's lead was last at 0 (a fault that ends late in a long stance: judged on the ticks
  // since its end).
  std::vector<StancePowers> stance_powers_, stance_cusum_;
  // A held gain's same comparison over a touchdown guard's ticks alone, judged on the first usable
  // tick after it (compare_held_gain_in_guard).
  std::vector<StancePowers> guard_powers_;
  double guard_powers_last_s_ = -1e300;  // the last guard tick they were kept on
  int stance_min_ticks_ = 50;  // round(clear_s / T), at least 2
  int usable_ticks_in_a_row_ = 0;  // ticks the stance comparison took in a row (capped)
  // The sum residual's level over those ticks: a first-order low-pass of time constant
  // stance_min_ticks_, seeded with the first tick's value, and the weight that seed still has.
  double residual_level_ = 0.0;
  double corrected_level_ = 0.0;  // the same low-pass of the corrected sum residual (offsets and drifts in it corrected)
  double residual_level_seed_weight_ = 1.0;
  double residual_level_gain_ = 0.02;  // 1 / stance_min_ticks_
  double gain_forgetting_ = 1.0;
  bool gain_unisolated_ = false;  // a strong gain fit that no single channel stands out in
  int gain_window_ticks_ = 1;
  // Substituted channels' loads: the sum and, on rigid soles, the plane relations.
  generic::UnmeasuredContactLoads unmeasured_{{}, 1, 1};
  std::vector<char> unknown_;         // per channel, this tick
  std::vector<double> lower_bound_;   // per channel, this tick
  std::vector<char> plane_usable_;    // per foot, this tick
  // Jumps inside a touchdown guard, confirmed by the foot's plane relations (the impact, which the
  // trunk IMU does not see, leaves a rigid sole's loads on a plane). Per foot: the relations of the
  // readings (as the jump test's sum takes them) over 2 jump windows, how long the foot has been in
  // full contact, the pending group's age and expected step, and the fault-free mean square
  // of the relations' window steps.
  std::vector<double> relation_ring_;     // feet x relations x 2 W
  std::vector<std::size_t> full_contact_run_;  // per foot: ticks in a row in full contact, at most 2 W
  std::size_t relation_next_ = 0;
  std::vector<char> relation_group_;      // per foot: 0 none, 1 pending, 2 decided this tick
  std::vector<int> relation_group_size_;  // per foot: the members of the group decided this tick
  std::vector<int> relation_group_age_;
  std::vector<double> relation_expect_;   // feet x relations: sum of w_j x jump_j over the group
  std::vector<double> relation_step_;     // feet x relations: this tick's window step
  std::vector<double> relation_before_;   // feet x relations: the mean of the window before
  std::vector<char> relation_step_known_; // per foot: the ring is full and in full contact
  std::vector<char> relation_verdict_;    // per foot: its group decided and confirmed, this tick
  std::vector<double> relation_step_square_;  // feet x relations
  std::vector<double> relation_step_count_;   // per foot
  double relation_z_ = 6.0;  // the two-sided normal quantile of alpha = T / false_alarm_interval_s
  double rocking_bar_N_ = std::numeric_limits<double>::infinity();  // z sqrt(3/2) sigma_x [N]: a pad's one-tick excursion beyond its noise
  double step_back_bar_N_ = std::numeric_limits<double>::infinity();  // z sqrt(2) sigma_x [N]: a one-tick change beyond its noise
  double reading_sigma_N_ = 2.0;  // sigma_x = sqrt(noise_std_N^2 + resolution_N^2 / 12)
};

}  // namespace ftsense::biped
