# cmake -P: installs BUILD_DIR into DESTDIR and checks that every file a deployment needs is
# where config/gearpathd.service and the docs say it is, and that the installed daemon runs.
file(REMOVE_RECURSE ${DESTDIR})
execute_process(COMMAND ${CMAKE_COMMAND} -E env DESTDIR=${DESTDIR}
                        ${CMAKE_COMMAND} --install ${BUILD_DIR}
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc}): ${err}")
endif()
foreach(f ${PREFIX}/bin/gearpathd ${PREFIX}/bin/gearpath ${SYSCONFDIR}/gearpath/gearpathd.json
          ${UNITDIR}/gearpathd.service ${PREFIX}/share/doc/gearpath/README.md
          ${PREFIX}/share/doc/gearpath/configuration.md ${PREFIX}/share/doc/gearpath/method.md
          ${PREFIX}/share/gearpath/idl/gearpath.idl
          ${PREFIX}/share/gearpath/fastdds/fastdds-profiles.xml)
  if(NOT EXISTS ${DESTDIR}${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
# The installed daemon accepts the installed configuration (what ExecStartPre runs).
execute_process(COMMAND ${DESTDIR}${PREFIX}/bin/gearpathd --check-config
                        --config ${DESTDIR}${SYSCONFDIR}/gearpath/gearpathd.json
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "installed gearpathd --check-config failed (${rc}): ${out}${err}")
endif()
file(REMOVE_RECURSE ${DESTDIR})
