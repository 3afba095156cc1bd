// Placeholder: argument parsing moves here from main.cpp.
#include "options.hpp"
