/* Nimbus SDK: everything a plugin needs, in one include. */
#ifndef NIMBUS_NIMBUS_H
#define NIMBUS_NIMBUS_H

#include "base.h"
#include "bsdf.h"
#include "film.h"
#include "guiding.h"
#include "host.h"
#include "integrator.h"
#include "light_sampler.h"
#include "lights.h"
#include "plugin.h"
#include "render_state.h"
#include "rng.h"
#include "scene.h"
#include "spectral.h"
#include "status.h"
#include "version.h"

#endif /* NIMBUS_NIMBUS_H */
