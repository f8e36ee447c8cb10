// An EngineState (server/core/engine_state.h) as bytes and back, for the processes of a split
// server: process 0 hands a checkpoint's state to the others, which restore their shares from it.
#pragma once

#include <vector>

#include "server/core/engine_state.h"

namespace cascade {

std::vector<char> state_message(const EngineState& state);
// Throws std::invalid_argument where the bytes end early or run on.
EngineState state_from_message(const std::vector<char>& message);

}  // namespace cascade
