/* Input of bindgen for src/mujoco/ffi.rs (see build.rs, feature `regen-bindings`). */
#include <mujoco/mujoco.h>
#include <GL/osmesa.h>
