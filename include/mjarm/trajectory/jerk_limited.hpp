#pragma once
/// @file
/// The generator's former path (before the trajectory/otg/ sub-room): include otg/generator.hpp.
#include "mjarm/trajectory/otg/generator.hpp"
