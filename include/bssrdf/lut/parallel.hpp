// Kept for code that includes the loop by its old name: the loop is bssrdf/parallel.hpp's.
#pragma once

#include "bssrdf/parallel.hpp"
