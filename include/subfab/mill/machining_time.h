// SPDX-License-Identifier: GPL-3.0-or-later
//! \file machining_time.h
//! Machining time of a toolpath on a machine that accelerates: a
//! trapezoidal speed profile per move (accelerate at `accel`, cruise at the
//! move's feed, decelerate), the speed through each corner limited the way
//! GRBL's planner limits it (junction deviation: the speed at which a
//! circular arc of deviation `junction_deviation` through the corner needs
//! `accel` of centripetal acceleration), and the look-ahead of GRBL and
//! LinuxCNC approximated by planning the whole path at once (a backward pass
//! so the tool can always stop in time, then a forward pass). The tool
//! starts and ends at rest. One acceleration for every axis (Z is often
//! slower on a hobby machine: set the lowest).
#pragma once

#include "subfab/mill/toolpath.h"

namespace subfab {

struct MotionLimits {
  double accel = 500.0;               // --accel: mm/s^2 (a hobby router's; GRBL's own default is 10)
  double junction_deviation = 0.01;   // mm (GRBL's $11 default)
};

//! Estimated time in seconds of `path` (starting from (0, 0, safe_z) at
//! rest), each move at its feed (Cut: feeds.feed, Plunge: feeds.plunge,
//! Rapid: feeds.rapid, mm/min). At least machining_time(path_lengths(path),
//! feeds), the same when accel is infinite.
//! \throw InvalidArgumentError when accel or the deviation is not positive.
double machining_time(const Toolpath& path, const Feeds& feeds, const MotionLimits& limits);

}  // namespace subfab
