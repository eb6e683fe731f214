#include "tfmb/common/errors.hpp"
