// Umbrella header of libtop, the TOP protocol library.
#pragma once

#include "top/catalog.hpp"
#include "top/decode.hpp"
#include "top/device.hpp"
#include "top/diagnoses.hpp"
#include "top/dialect.hpp"
#include "top/findings.hpp"
#include "top/frame.hpp"
#include "top/motion.hpp"
#include "top/probe.hpp"
#include "top/stream.hpp"
#include "top/text.hpp"
