# What the packages install besides the binaries, plugins, SDK, OCIO config and scenes (CMakeLists.txt):
# the Slurm scripts (packaging/slurm), bash completion, the Debian copyright and changelog, and man pages
# for nimbus, each subcommand and nimbus-slurm-submit, generated from their --help texts by help2man at
# build time so that they never diverge. All in the `runtime` component.

install(PROGRAMS packaging/slurm/nimbus-slurm-submit DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
install(PROGRAMS packaging/slurm/nimbus-render-task.sbatch packaging/slurm/nimbus-merge.sbatch
  DESTINATION ${NIMBUS_INSTALL_DATA_DIR}/slurm COMPONENT runtime)
install(FILES packaging/slurm/README.md DESTINATION ${NIMBUS_INSTALL_DATA_DIR}/slurm COMPONENT runtime)
install(FILES packaging/completion/nimbus DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions
  COMPONENT runtime)

# Debian wants the changelog gzipped (-n: no timestamp, so the package is reproducible); its newest entry
# must be this version.
file(STRINGS packaging/debian/changelog changelog_head LIMIT_COUNT 1)
if(NOT changelog_head MATCHES "^nimbus \\(${PROJECT_VERSION}\\)")
  message(FATAL_ERROR "packaging/debian/changelog starts with '${changelog_head}': add an entry for "
    "nimbus (${PROJECT_VERSION}) at its top")
endif()
set(nimbus_doc_dir ${CMAKE_INSTALL_DATADIR}/doc/nimbus)
add_custom_command(OUTPUT ${PROJECT_BINARY_DIR}/packaging/changelog.Debian.gz
  COMMAND gzip -9n -c ${PROJECT_SOURCE_DIR}/packaging/debian/changelog > ${PROJECT_BINARY_DIR}/packaging/changelog.Debian.gz
  DEPENDS packaging/debian/changelog VERBATIM)
add_custom_target(nimbus_changelog ALL DEPENDS ${PROJECT_BINARY_DIR}/packaging/changelog.Debian.gz)
install(FILES packaging/debian/copyright ${PROJECT_BINARY_DIR}/packaging/changelog.Debian.gz
  DESTINATION ${nimbus_doc_dir} COMPONENT runtime)

find_program(HELP2MAN_PROGRAM help2man)
if(TARGET nimbus AND HELP2MAN_PROGRAM)
  set(man_dir ${PROJECT_BINARY_DIR}/packaging/man)
  set(man_pages)
  # name, what help2man runs (`-`: nimbus itself; a subcommand runs through a wrapper named like the page,
  # so that the page's title is its name; else a path), summary
  set(pages
    "nimbus|-|progressive CPU renderer with a one-click caustics solver"
    "nimbus-render|render|render a scene to a multi-layer EXR and a PNG preview"
    "nimbus-merge|merge|join the partial EXRs of a frame rendered as tasks"
    "nimbus-plugins|plugins|list the plugins found, with their status"
    "nimbus-lightmix|lightmix|relight a LightMix render"
    "nimbus-compare|compare|error metrics of an EXR against a reference"
    "nimbus-slurm-submit|${PROJECT_SOURCE_DIR}/packaging/slurm/nimbus-slurm-submit|render one frame across a Slurm cluster")
  foreach(page ${pages})
    string(REPLACE "|" ";" fields "${page}")
    list(GET fields 0 name)
    list(GET fields 1 program)
    list(GET fields 2 summary)
    if(program STREQUAL "-")
      set(program $<TARGET_FILE:nimbus>)
    elseif(NOT program MATCHES "/")  # a subcommand: a wrapper script `nimbus-<command>` runs `nimbus <command>`
      file(GENERATE OUTPUT ${man_dir}/bin/${name}
        CONTENT "#!/bin/sh\nexec \"$<TARGET_FILE:nimbus>\" ${program} \"$@\"\n"
        FILE_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE WORLD_READ WORLD_EXECUTE)
      set(program ${man_dir}/bin/${name})
    endif()
    add_custom_command(OUTPUT ${man_dir}/${name}.1.gz
      COMMAND ${HELP2MAN_PROGRAM} --no-info --section 1 --name "${summary}"
        --version-string "${PROJECT_VERSION}" --source "Nimbus ${PROJECT_VERSION}" --manual "Nimbus"
        --output ${man_dir}/${name}.1 ${program}
      COMMAND gzip -9nf ${man_dir}/${name}.1
      DEPENDS nimbus ${PROJECT_SOURCE_DIR}/packaging/slurm/nimbus-slurm-submit VERBATIM)
    list(APPEND man_pages ${man_dir}/${name}.1.gz)
  endforeach()
  add_custom_target(nimbus_man ALL DEPENDS ${man_pages})
  install(FILES ${man_pages} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 COMPONENT runtime)
elseif(TARGET nimbus)
  message(WARNING "help2man not found (apt-get install help2man): the packages will have no man pages")
endif()
