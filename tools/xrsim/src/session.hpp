#pragma once
// Session lifecycle transitions used by the frame loop as well as the session entry points.
#include "objects.hpp"

namespace xrsim {

/// Walks a running session down to STOPPING (FOCUSED -> VISIBLE -> SYNCHRONIZED -> STOPPING).
void stopSession(Session& session);
/// Simulates the loss of the session (LOSS_PENDING) or of the whole instance.
void loseSession(Session& session);

}  // namespace xrsim
