/* Nimbus SDK: the ABI version of these headers. Includes base.h (conventions, export macros, the
 * struct header) and status.h (status codes), which every other header relies on. */
#ifndef NIMBUS_VERSION_H
#define NIMBUS_VERSION_H

#include <stdint.h>

#include "base.h"
#include "status.h"

/* The ABI these headers describe. A plugin loads iff its major equals the host's and its minor is not
 * newer; in 0.x the minor must match exactly. Patch never matters.
 * A minor only appends: members marked "Since 1.N" exist in tables built with SDK 1.N or later, so a
 * caller holding a table from an older plugin or host checks NIMBUS_HAS_MEMBER before using them.
 * Changelog: docs/sdk-guide.md. Frozen copies of each minor's headers: tests/abi/sdk-1.N/. */
#define NIMBUS_ABI_MAJOR 1
#define NIMBUS_ABI_MINOR 10
#define NIMBUS_ABI_PATCH 0

typedef struct nimbus_version {
  uint16_t major, minor, patch, reserved;
} nimbus_version_t;

#define NIMBUS_ABI_VERSION_INIT \
  { NIMBUS_ABI_MAJOR, NIMBUS_ABI_MINOR, NIMBUS_ABI_PATCH, 0 }

#endif /* NIMBUS_VERSION_H */
