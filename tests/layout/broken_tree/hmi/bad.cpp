// A source that breaks the HMI's include rule, for the checker's own test.
#include "rt/shm_interface.h"
#include "rt/rt_kernel.h"
