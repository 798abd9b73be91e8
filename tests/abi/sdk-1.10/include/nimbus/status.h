/* Nimbus SDK: status codes of fallible calls (sdk-idioms.md 1.6). */
#ifndef NIMBUS_STATUS_H
#define NIMBUS_STATUS_H

#include <stdint.h>

/* Status of fallible calls. Zero is success; any negative value is a failure, including values this
 * header does not know yet. */
typedef int32_t nimbus_status_t;
#define NIMBUS_OK 0
#define NIMBUS_E_INVALID_ARG (-1)
#define NIMBUS_E_UNSUPPORTED (-2)
#define NIMBUS_E_NO_MEMORY (-3)
#define NIMBUS_E_VERSION (-4)
#define NIMBUS_E_CANCELLED (-5)
#define NIMBUS_E_INTERNAL (-6)

#endif /* NIMBUS_STATUS_H */
