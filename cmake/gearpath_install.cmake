# Install layout and the Debian package (cpack -G DEB in the build directory).
#
# With the default prefix /usr (set in the top-level CMakeLists.txt before this file):
#   /usr/bin/gearpathd, /usr/bin/gearpath                 the daemon and the tools
#   /etc/gearpath/gearpathd.json                          the configuration (a conffile)
#   /lib/systemd/system/gearpathd.service                 the hardened unit, not enabled
#   /usr/share/doc/gearpath/                              README and docs/*.md
#   /usr/share/gearpath/idl/gearpath.idl                  the DDS contract, for other vendors
#   /usr/share/gearpath/fastdds/fastdds-profiles.xml      Fast DDS client profiles (deployment.md)
#   /usr/share/man/man8/gearpathd.8.gz, man1/gearpath.1.gz  man pages made from --help by help2man
# The unit and the paths in it are those of config/gearpathd.service.
include(GNUInstallDirs)

install(TARGETS gearpathd gearpath RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES config/gearpathd.json DESTINATION ${CMAKE_INSTALL_FULL_SYSCONFDIR}/gearpath)
set(GEARPATH_SYSTEMD_UNIT_DIR "/lib/systemd/system" CACHE PATH
    "Where the systemd unit is installed")
install(FILES config/gearpathd.service DESTINATION ${GEARPATH_SYSTEMD_UNIT_DIR})
install(FILES README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
file(GLOB gearpath_docs CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/docs/*.md)
install(FILES ${gearpath_docs} DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(FILES idl/gearpath.idl DESTINATION ${CMAKE_INSTALL_DATADIR}/gearpath/idl)
install(FILES config/fastdds-profiles.xml DESTINATION ${CMAKE_INSTALL_DATADIR}/gearpath/fastdds)

# Man pages generated from the programs' own --help and --version, so they cannot drift from the
# options (help2man, tools/install-deps.sh). The daemon is an administrator's command (8).
find_program(GEARPATH_HELP2MAN help2man)
if(GEARPATH_HELP2MAN)
  set(gearpath_man_pages)
  foreach(entry "gearpathd;8;gearbox condition-monitoring daemon: transfer path analysis over DDS"
                "gearpath;1;gearpathd's companion: simulate, replay, monitor, report, evaluate")
    list(GET entry 0 program)
    list(GET entry 1 section)
    list(GET entry 2 summary)
    set(page ${CMAKE_CURRENT_BINARY_DIR}/man/${program}.${section})
    add_custom_command(
      OUTPUT ${page}.gz
      COMMAND ${CMAKE_COMMAND} -E make_directory ${CMAKE_CURRENT_BINARY_DIR}/man
      COMMAND ${GEARPATH_HELP2MAN} --no-info --no-discard-stderr --section=${section}
              --name=${summary} --output=${page} $<TARGET_FILE:${program}>
      COMMAND gzip -9nf ${page}
      DEPENDS ${program}
      COMMENT "man page ${program}(${section}) from its --help"
      VERBATIM)
    list(APPEND gearpath_man_pages ${page}.gz)
    install(FILES ${page}.gz DESTINATION ${CMAKE_INSTALL_MANDIR}/man${section})
  endforeach()
  add_custom_target(gearpath_man_pages ALL DEPENDS ${gearpath_man_pages})
else()
  message(WARNING "help2man not found: no man pages (tools/install-deps.sh installs it)")
endif()

set(CPACK_PACKAGE_NAME gearpath)
set(CPACK_PACKAGE_VENDOR "gearpath")
set(CPACK_PACKAGE_CONTACT "gearpath maintainers <gearpath@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Gearbox condition monitoring by transfer path analysis over DDS")
set(CPACK_PACKAGE_DESCRIPTION
    "gearpathd identifies bearing forces from streamed housing accelerations with decoupled FRFs, computes every transfer path's contribution and publishes the dominant path, the suspected gear and the condition indicators as DDS topics; gearpath is its command-line companion (simulation, replay, monitor, report, evaluation).")
set(CPACK_GENERATOR DEB)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
# The shared libraries the binaries link (Cyclone DDS, FFTW, spdlog, fmt, systemd) become
# package dependencies through dpkg-shlibdeps.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# Debug information stays in the build tree (RelWithDebInfo binaries are ~150 MB each).
set(CPACK_STRIP_FILES ON)
# The configuration is the administrator's: an upgrade must not overwrite an edited one.
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/debian/conffiles
     "${CMAKE_INSTALL_FULL_SYSCONFDIR}/gearpath/gearpathd.json\n")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${CMAKE_CURRENT_BINARY_DIR}/debian/conffiles)
include(CPack)
