/* expect: nimbus_plugin_entry: returns a pointer */

/* [main-thread] The entry. */
NIMBUS_EXPORT const nimbus_entry_t *nimbus_plugin_entry(void);
