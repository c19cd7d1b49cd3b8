// The capture room's API for file inputs in one include: the sink, times,
// inputs and formats, link dissection and the readers. Live inputs are in
// capture/live.hpp.
#pragma once

#include "capture/input.hpp"
#include "capture/link.hpp"
#include "capture/read.hpp"
#include "capture/sink.hpp"
#include "capture/time.hpp"
