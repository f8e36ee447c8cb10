// `cascade ensemble SIM (--rain-factors F,F,... | --hyetograph FILE...) [--time-unit U]
// [--intensity-unit U] [--until T] [--stop-after KIND[:S]] [--out FILE.csv]`: what-if branches of
// one simulation. Each branch is a fork (ForkSimulation) from the same step, with the case's rain
// times a factor (rainfall.factor) or a hyetograph of its own from the fork on (each row's
// intensity from the first step boundary at or after its time); all run side by side to T
// (default the case's end), each stopping S simulated seconds after its own first cascade event
// KIND when given (e.g. landslide_onset:3: each forecast a few seconds past its own failure), and
// the table gives each branch's events: ponding, the landslide's onset, the water's impact, the
// wave's arrival and height at each gauge, the overtopping. A running parent pauses for the forks
// and goes on after them.
#pragma once

#include "clients/cli/remote.h"

namespace cascade::cli {

int ensemble(Remote& remote);

}  // namespace cascade::cli
