// What an interface needs to inspect a frame's buffers beside Session itself: the display
// request Session::setDisplay takes (what the viewport shows, how it is scaled), the decoders
// that say what a stored value means (a resource's ResourceDesc::decoder: its companions,
// meaning views, probe lines), and the names of the views the panels offer. The editor
// reaches lighting through the session's headers only (tested: cli.editor_reaches_lighting_through_session).
#pragma once

#include "lighting/common/decoders.h"
#include "lighting/common/display_pass.h"
#include "lighting/common/redeferred_pass.h"

namespace tl::session {

// The redeferred frame's light alone (ibuffer.lightOnly): a view the Lighting panel offers.
using lighting::kIbufferLightOnly;

}  // namespace tl::session
