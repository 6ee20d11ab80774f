# cmake -P: the Debian package (cmake/gearpath_install.cmake, `cpack -G DEB`) built from BUILD_DIR
# and installed with dpkg into a staging root, as the issue's bar asks ("the Debian package builds
# in CI and installs into a staging root; gearpathd --version runs from there"):
#   1. cpack makes exactly one gearpath_<version>_<arch>.deb (into WORK, not the build tree);
#   2. its control fields: name, version and architecture; Depends holds the Debian package of
#      every shared library the two binaries need, found independently of dpkg-shlibdeps (the
#      binaries' NEEDED entries resolved by ldd, each looked up with dpkg -S), and no -dev
#      package; the conffile is /etc/gearpath/gearpathd.json;
#   3. dpkg --root installs it into WORK/root with its own database: the package is "install ok
#      installed", dpkg recorded the conffile with the staged file's md5, the binaries are
#      stripped, and the unit's ExecStart/ExecStartPre name a staged binary and configuration;
#   4. the staged `gearpathd --version` and `gearpath --version` say VERSION, and the staged
#      `gearpathd --check-config` accepts the staged configuration (what ExecStartPre runs);
#   5. `dpkg -r` removes the binaries and keeps the (conf)file; `dpkg -P` then removes it.
# Inputs: BUILD_DIR, WORK, VERSION, PREFIX, SYSCONFDIR, UNITDIR, BINARIES (;-list, the built ones).
cmake_minimum_required(VERSION 3.25)  # the project's policies (IN_LIST, REAL_PATH) in script mode

function(run_checked what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${ARGN}\n${out}${err}")
  endif()
  set(run_out "${out}" PARENT_SCOPE)
endfunction()

foreach(tool dpkg dpkg-deb dpkg-query dpkg-shlibdeps ldd readelf)
  find_program(have_${tool} ${tool})
  if(NOT have_${tool})
    message(FATAL_ERROR "${tool} not found: the package test needs dpkg-dev and binutils "
                        "(bash tools/install-deps.sh installs them)")
  endif()
endforeach()
get_filename_component(cmake_dir ${CMAKE_COMMAND} DIRECTORY)
find_program(cpack_command cpack HINTS ${cmake_dir} NO_DEFAULT_PATH)
if(NOT cpack_command)
  find_program(cpack_command cpack REQUIRED)
endif()

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

# 1. The package.
run_checked("cpack -G DEB" ${cpack_command} --config ${BUILD_DIR}/CPackConfig.cmake -G DEB
            -B ${WORK}/cpack)
file(GLOB debs ${WORK}/cpack/*.deb)
list(LENGTH debs n_debs)
if(NOT n_debs EQUAL 1)
  message(FATAL_ERROR "expected one .deb in ${WORK}/cpack, found ${n_debs}: ${debs}")
endif()
set(deb ${debs})
run_checked("dpkg --print-architecture" dpkg --print-architecture)
string(STRIP "${run_out}" arch)
get_filename_component(deb_name ${deb} NAME)
if(NOT deb_name STREQUAL "gearpath_${VERSION}_${arch}.deb")
  message(FATAL_ERROR "package file ${deb_name}, expected gearpath_${VERSION}_${arch}.deb")
endif()

# 2. Control fields.
function(control_field field out_var)
  run_checked("dpkg-deb -f ${field}" dpkg-deb -f ${deb} ${field})
  string(STRIP "${run_out}" value)
  set(${out_var} "${value}" PARENT_SCOPE)
endfunction()
control_field(Package package)
control_field(Version version)
control_field(Architecture architecture)
control_field(Depends depends)
if(NOT package STREQUAL "gearpath" OR NOT version STREQUAL "${VERSION}" OR
   NOT architecture STREQUAL "${arch}")
  message(FATAL_ERROR "control: Package '${package}' Version '${version}' Architecture "
                      "'${architecture}', expected gearpath ${VERSION} ${arch}")
endif()
# "libfoo1 (>= 1.2), libbar2" -> names
string(REGEX REPLACE "\\([^)]*\\)" "" depends_names "${depends}")
string(REGEX REPLACE "[ \t\n]" "" depends_names "${depends_names}")
string(REPLACE "|" "," depends_names "${depends_names}")
string(REPLACE "," ";" depends_names "${depends_names}")
foreach(d ${depends_names})
  if(d MATCHES "-dev$")
    message(FATAL_ERROR "Depends names a development package: ${d} (Depends: ${depends})")
  endif()
endforeach()

# Every shared library the binaries load, by the package that ships it (dpkg's own database).
set(expected_packages "")
foreach(binary ${BINARIES})
  # The libraries the binary itself names (NEEDED; what dpkg-shlibdeps reads), where ldd finds
  # them. Their own dependencies are their packages' business.
  run_checked("readelf -d ${binary}" readelf -d --wide ${binary})
  string(REGEX MATCHALL "\\(NEEDED\\)[^\n]*" needed_entries "${run_out}")
  run_checked("ldd ${binary}" ldd ${binary})
  set(ldd_out "${run_out}")
  set(libs "")
  foreach(entry ${needed_entries})
    string(REGEX REPLACE ".*\\[(.*)\\].*" "\\1" soname "${entry}")
    # Found by plain text, not a regex: sonames hold regex characters (libstdc++.so.6).
    string(FIND "${ldd_out}" "\t${soname} => /" at)
    if(at GREATER_EQUAL 0)
      string(SUBSTRING "${ldd_out}" ${at} -1 rest)
      string(REGEX MATCH "=> (/[^ \n]+)" found "${rest}")
      list(APPEND libs ${CMAKE_MATCH_1})
    else()
      # The dynamic loader, when the binary names it (glibc 2.36: ld-linux-x86-64.so.2), is
      # listed by ldd under its path alone: "\t/lib64/ld-linux-x86-64.so.2 (0x...)".
      string(FIND "${ldd_out}" "/${soname} (" at)
      if(at LESS 0)
        message(FATAL_ERROR "${binary} needs ${soname}, which ldd does not resolve:\n${ldd_out}")
      endif()
      string(SUBSTRING "${ldd_out}" 0 ${at} before)
      string(REGEX MATCH "\t(/[^ \t\n]*)$" found "${before}")
      list(APPEND libs "${CMAKE_MATCH_1}/${soname}")
    endif()
  endforeach()
  if(NOT libs)
    message(FATAL_ERROR "readelf found no NEEDED library in ${binary}:\n${run_out}")
  endif()
  foreach(lib ${libs})
    file(REAL_PATH ${lib} real)
    # usrmerge: dpkg knows a library under the path its package ships, /lib or /usr/lib.
    set(owner "")
    foreach(candidate ${lib} ${real})
      string(REGEX REPLACE "^/usr/lib/" "/lib/" as_lib ${candidate})
      string(REGEX REPLACE "^/lib/" "/usr/lib/" as_usr_lib ${candidate})
      foreach(path ${candidate} ${as_lib} ${as_usr_lib})
        execute_process(COMMAND dpkg -S ${path} RESULT_VARIABLE rc OUTPUT_VARIABLE found
                        ERROR_QUIET)
        if(rc EQUAL 0)
          string(REGEX REPLACE ":.*" "" owner "${found}")  # "libfoo1:amd64: /path" -> libfoo1
          break()
        endif()
      endforeach()
      if(owner)
        break()
      endif()
    endforeach()
    if(NOT owner)
      message(FATAL_ERROR "${binary} loads ${lib}, which no installed Debian package ships: "
                          "the package could not depend on it")
    endif()
    list(APPEND expected_packages ${owner})
  endforeach()
endforeach()
list(REMOVE_DUPLICATES expected_packages)
foreach(p ${expected_packages})
  # Depends may name the package or a virtual package it provides: the shlibs file of Debian's
  # libspdlog1.10 says libspdlog1.10-fmt9, which libspdlog1.10 Provides.
  run_checked("dpkg-query Provides ${p}" dpkg-query -W -f=\${Provides} ${p})
  string(REGEX REPLACE "\\([^)]*\\)" "" provides "${run_out}")
  string(REGEX REPLACE "[ \t\n]" "" provides "${provides}")
  string(REPLACE "," ";" provides "${provides}")
  set(named FALSE)
  foreach(name ${p} ${provides})
    if(name IN_LIST depends_names)
      set(named TRUE)
    endif()
  endforeach()
  if(NOT named)
    message(FATAL_ERROR "the binaries load a library of ${p} (provides: '${provides}'), but "
                        "Depends names neither: ${depends}")
  endif()
endforeach()
# The daemon's own stack is among them (a guard against an ldd that resolved nothing useful).
foreach(p libddsc0debian libfftw3-double3 libc6 libstdc++6)
  if(NOT p IN_LIST depends_names)
    message(FATAL_ERROR "Depends lacks ${p}: ${depends}")
  endif()
endforeach()

run_checked("dpkg-deb -e" dpkg-deb -e ${deb} ${WORK}/control)
file(READ ${WORK}/control/conffiles conffiles)
string(STRIP "${conffiles}" conffiles)
if(NOT conffiles STREQUAL "${SYSCONFDIR}/gearpath/gearpathd.json")
  message(FATAL_ERROR "conffiles: '${conffiles}', expected ${SYSCONFDIR}/gearpath/gearpathd.json")
endif()

# 3. Installed by dpkg into a staging root with its own (empty) database. The dependencies are
# installed on this host, not in the root: --force-depends. The package has no maintainer
# scripts, so nothing runs chrooted.
set(root ${WORK}/root)
set(admin ${root}/var/lib/dpkg)
file(MAKE_DIRECTORY ${admin}/info ${admin}/updates ${admin}/triggers ${root}/var/log)
file(WRITE ${admin}/status "")
file(WRITE ${admin}/available "")
set(dpkg_staged dpkg --root=${root} --admindir=${admin} --log=${WORK}/dpkg.log --force-depends
    --force-script-chrootless)
execute_process(COMMAND id -u OUTPUT_VARIABLE uid OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT uid STREQUAL "0")
  list(APPEND dpkg_staged --force-not-root)
endif()
run_checked("dpkg -i into ${root}" ${dpkg_staged} -i ${deb})
run_checked("dpkg-query" dpkg-query --admindir=${admin} -W -f=\${Status}|\${Version}|\${Conffiles}
            gearpath)
string(STRIP "${run_out}" query)
string(REGEX REPLACE "\\|[ \n]+" "|" query "${query}")  # Conffiles is a multi-line field
file(MD5 ${root}${SYSCONFDIR}/gearpath/gearpathd.json staged_md5)
set(expected_query "install ok installed|${VERSION}|${SYSCONFDIR}/gearpath/gearpathd.json ${staged_md5}")
if(NOT query STREQUAL expected_query)
  message(FATAL_ERROR "dpkg-query in the staging root: '${query}', expected '${expected_query}'")
endif()

foreach(f ${PREFIX}/bin/gearpathd ${PREFIX}/bin/gearpath ${SYSCONFDIR}/gearpath/gearpathd.json
          ${UNITDIR}/gearpathd.service ${PREFIX}/share/doc/gearpath/README.md
          ${PREFIX}/share/doc/gearpath/deployment.md ${PREFIX}/share/gearpath/idl/gearpath.idl
          ${PREFIX}/share/gearpath/fastdds/fastdds-profiles.xml)
  if(NOT EXISTS ${root}${f})
    message(FATAL_ERROR "not in the staging root after dpkg -i: ${f}")
  endif()
endforeach()
# The man pages are the programs' own --help (help2man): their NAME line and an option of each.
foreach(page "man8/gearpathd.8.gz;gearpathd \\- gearbox condition-monitoring daemon;\\-\\-check\\-config"
             "man1/gearpath.1.gz;gearpath \\- gearpathd's companion;evaluate")
  list(GET page 0 file)
  list(GET page 1 name_line)
  list(GET page 2 option)
  set(path ${root}${PREFIX}/share/man/${file})
  if(NOT EXISTS ${path})
    message(FATAL_ERROR "no man page in the staging root after dpkg -i: ${PREFIX}/share/man/${file}")
  endif()
  run_checked("gzip -dc ${file}" gzip -dc ${path})
  string(FIND "${run_out}" "${name_line}" at_name)
  string(FIND "${run_out}" "${option}" at_option)
  if(at_name LESS 0 OR at_option LESS 0)
    message(FATAL_ERROR "${file} lacks '${name_line}' or '${option}':\n${run_out}")
  endif()
endforeach()
foreach(b gearpathd gearpath)
  run_checked("readelf -S" readelf -S --wide ${root}${PREFIX}/bin/${b})
  if(run_out MATCHES "\\.debug_info")
    message(FATAL_ERROR "${PREFIX}/bin/${b} in the package is not stripped")
  endif()
endforeach()

# The unit runs what the package installed.
file(STRINGS ${root}${UNITDIR}/gearpathd.service exec_lines REGEX "^ExecStart(Pre)?=")
list(LENGTH exec_lines n_exec)
if(NOT n_exec EQUAL 2)
  message(FATAL_ERROR "expected ExecStartPre= and ExecStart= in the unit, got: ${exec_lines}")
endif()
foreach(line ${exec_lines})
  string(REGEX REPLACE "^ExecStart(Pre)?=" "" command "${line}")
  separate_arguments(words UNIX_COMMAND "${command}")
  list(GET words 0 program)
  list(FIND words --config at)
  math(EXPR at "${at} + 1")
  list(GET words ${at} config)
  if(NOT EXISTS ${root}${program} OR NOT EXISTS ${root}${config})
    message(FATAL_ERROR "the unit's '${line}' names a file the package did not install")
  endif()
endforeach()
# ... and its Documentation= pages are the package's docs (/usr/share/doc/gearpath).
file(STRINGS ${root}${UNITDIR}/gearpathd.service doc_lines REGEX "^Documentation=")
if(NOT doc_lines)
  message(FATAL_ERROR "no Documentation= line in the unit")
endif()
foreach(line ${doc_lines})
  string(REGEX REPLACE "^Documentation=" "" urls "${line}")
  separate_arguments(urls UNIX_COMMAND "${urls}")
  foreach(url ${urls})
    if(url MATCHES "^file://(/.*)$" AND NOT EXISTS ${root}${CMAKE_MATCH_1})
      message(FATAL_ERROR "the unit's Documentation= names ${url}, which the package lacks")
    endif()
  endforeach()
endforeach()

# 4. The staged binaries run.
foreach(b gearpathd gearpath)
  run_checked("staged ${b} --version" ${root}${PREFIX}/bin/${b} --version)
  if(NOT run_out MATCHES "^${b} ${VERSION}\n?$")
    message(FATAL_ERROR "staged ${b} --version said '${run_out}', expected '${b} ${VERSION}'")
  endif()
endforeach()
run_checked("staged gearpathd --check-config" ${root}${PREFIX}/bin/gearpathd --check-config
            --config ${root}${SYSCONFDIR}/gearpath/gearpathd.json)

# 5. Remove keeps the configuration (a conffile), purge removes it.
run_checked("dpkg -r" ${dpkg_staged} -r gearpath)
if(EXISTS ${root}${PREFIX}/bin/gearpathd OR NOT EXISTS ${root}${SYSCONFDIR}/gearpath/gearpathd.json)
  message(FATAL_ERROR "after dpkg -r: the binary should be gone and the conffile kept")
endif()
run_checked("dpkg -P" ${dpkg_staged} -P gearpath)
if(EXISTS ${root}${SYSCONFDIR}/gearpath/gearpathd.json)
  message(FATAL_ERROR "after dpkg -P the conffile should be gone")
endif()

file(REMOVE_RECURSE ${WORK})
message(STATUS "package ${deb_name}: Depends ${depends}; installed, run and removed in a staging root")
