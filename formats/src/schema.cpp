#include "tfmb/formats/schema.hpp"
