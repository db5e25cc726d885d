#pragma once
/// @file
/// The reeving's law (rope ends, falls, the sheaves' efficiency) lives in model/reeving.hpp: compile
/// builds a rope's sheave losses from it (model/sheaves.hpp), and the model layer cannot include this one.
#include "machdyn/model/reeving.hpp"
