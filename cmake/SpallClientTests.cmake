# ctest label `client` (issue 23): spall's output opened by the real clients a
# user reaches for -- ParaView's pvbatch under a virtual X server, with the
# reader ParaView picks for .xdmf and with the legacy XDMF reader, and h5py.
# `make check` installs them first (scripts/install-test-deps.sh); without
# them the tests report "skipped" (exit 77), never "passed".
# Outputs (screenshots, logs) go to ${CMAKE_BINARY_DIR}/client.
# Labelled no_asan too: they test the file format, not memory safety, and the
# instrumented runs would only make `make asan` slower.  The pvbatch tests
# hold RESOURCE_LOCK spall_xvfb: started together under ctest -j, pvbatch
# often failed to open its virtual display ("bad X server connection").
if(SPALL_TESTS)
  set(SPALL_CLIENT_DIR ${CMAKE_BINARY_DIR}/client)
  set(SPALL_CLIENT_SRC ${CMAKE_SOURCE_DIR}/tests/client)
  # h5py is Debian's python3-h5py: /usr/bin/python3 even when another python3
  # (pyenv, venv) comes first in PATH.
  find_program(SPALL_DEBIAN_PYTHON3 python3 PATHS /usr/bin NO_DEFAULT_PATH)
  if(NOT SPALL_DEBIAN_PYTHON3)
    set(SPALL_DEBIAN_PYTHON3 python3)
  endif()
  set(SPALL_CLIENT_ENV "OMP_NUM_THREADS=2;OMP_WAIT_POLICY=passive")

  add_test(NAME client_runs
           COMMAND bash ${SPALL_CLIENT_SRC}/runs.sh $<TARGET_FILE:spall> ${CMAKE_SOURCE_DIR}
                   ${SPALL_CLIENT_DIR}/runs)
  set_tests_properties(client_runs PROPERTIES FIXTURES_SETUP client_runs LABELS "client;no_asan"
                       ENVIRONMENT "${SPALL_CLIENT_ENV}" TIMEOUT 900)

  # the array each screenshot is coloured by (every array is checked)
  set(SPALL_CLIENT_COLOR_epoxy_holes strain_energy)
  set(SPALL_CLIENT_COLOR_sph_taylor_3d pressure)
  set(SPALL_CLIENT_COLOR_impact_vinylester velocity)
  set(SPALL_CLIENT_COLOR_sph_taylor_2d deviatoric_stress)
  foreach(run epoxy_holes sph_taylor_3d impact_vinylester sph_taylor_2d)
    foreach(reader default legacy)
      add_test(NAME client_pv_${run}_${reader}
               COMMAND bash ${SPALL_CLIENT_SRC}/pvbatch.sh ${SPALL_CLIENT_SRC}/pv_check.py
                       --xdmf ${SPALL_CLIENT_DIR}/runs/${run}/fields.xdmf --reader ${reader}
                       --png ${SPALL_CLIENT_DIR}/${run}_${reader}.png --color ${SPALL_CLIENT_COLOR_${run}})
      set_tests_properties(client_pv_${run}_${reader} PROPERTIES FIXTURES_REQUIRED client_runs
                           LABELS "client;no_asan" SKIP_RETURN_CODE 77 TIMEOUT 300
                           RESOURCE_LOCK spall_xvfb)
    endforeach()
  endforeach()
  # bonds as line cells (bonds.xdmf) of a cracked lattice plate
  foreach(reader default legacy)
    add_test(NAME client_pv_bonds_${reader}
             COMMAND bash ${SPALL_CLIENT_SRC}/pvbatch.sh ${SPALL_CLIENT_SRC}/pv_bonds.py
                     --dir ${SPALL_CLIENT_DIR}/runs/plate_bonds --reader ${reader}
                     --png ${SPALL_CLIENT_DIR}/plate_bonds_${reader}.png)
    set_tests_properties(client_pv_bonds_${reader} PROPERTIES FIXTURES_REQUIRED client_runs
                         LABELS "client;no_asan" SKIP_RETURN_CODE 77 TIMEOUT 300
                         RESOURCE_LOCK spall_xvfb)
  endforeach()
  add_test(NAME client_pv_no_connectivity
           COMMAND bash ${SPALL_CLIENT_SRC}/no_connectivity.sh ${CMAKE_SOURCE_DIR}
                   ${SPALL_CLIENT_DIR}/runs ${SPALL_CLIENT_DIR} ${SPALL_DEBIAN_PYTHON3})
  set_tests_properties(client_pv_no_connectivity PROPERTIES FIXTURES_REQUIRED client_runs
                       LABELS "client;no_asan" SKIP_RETURN_CODE 77 TIMEOUT 300
                           RESOURCE_LOCK spall_xvfb)
  foreach(run epoxy_holes sph_taylor_3d impact_vinylester sph_taylor_2d)
    add_test(NAME client_h5py_${run}
             COMMAND bash -c "${SPALL_DEBIAN_PYTHON3} -c 'import h5py' 2>/dev/null || { echo 'client test skipped: python3-h5py not installed'; exit 77; }; exec ${SPALL_DEBIAN_PYTHON3} ${SPALL_CLIENT_SRC}/h5_user.py ${SPALL_CLIENT_DIR}/runs/${run}")
    set_tests_properties(client_h5py_${run} PROPERTIES FIXTURES_REQUIRED client_runs
                         LABELS "client;no_asan" SKIP_RETURN_CODE 77 TIMEOUT 120)
  endforeach()
endif()
if(SPALL_TESTS)
  add_test(NAME client_docs_snippets
           COMMAND bash ${SPALL_CLIENT_SRC}/doc_snippets.sh ${CMAKE_SOURCE_DIR}
                   ${SPALL_CLIENT_DIR}/runs/impact_vinylester ${SPALL_DEBIAN_PYTHON3})
  set_tests_properties(client_docs_snippets PROPERTIES FIXTURES_REQUIRED client_runs
                       LABELS "client;no_asan" SKIP_RETURN_CODE 77 TIMEOUT 300
                           RESOURCE_LOCK spall_xvfb)
endif()
