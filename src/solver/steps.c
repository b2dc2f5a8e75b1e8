/* The method table: one step type per tt_method (stepper.h). */
#include "stepper.h"

const tt_step_type *const tt_step_types[3] = {
    [TT_METHOD_DOPRI5] = &tt_step_dopri5,
    [TT_METHOD_RK4] = &tt_step_rk4,
    [TT_METHOD_RADAU] = &tt_step_radau,
};
