// Every benchmark program finds the Stanford models and the textures in the shared folder beside
// the checkout: RAYLANE_MODEL_PATH names it unless the caller set the variable.
#include <cstdlib>

namespace {

const bool model_path_set =
    (::setenv("RAYLANE_MODEL_PATH", RAYLANE_SHARED_DIR "/models:" RAYLANE_SHARED_DIR "/textures",
              0),
     true);

}  // namespace
