# cmake -DBUILD=<build dir> -DSTAGE=<prefix> -P install_staged.cmake
# Installs the build into a staging prefix for the tests of the installed module, keeping
# the build's install_manifest.txt (what `make uninstall` removes) the real install's.
set(manifest "${BUILD}/install_manifest.txt")
if(EXISTS "${manifest}")
    file(RENAME "${manifest}" "${manifest}.real")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD}" --prefix "${STAGE}"
                RESULT_VARIABLE rc)
if(EXISTS "${manifest}.real")
    file(RENAME "${manifest}.real" "${manifest}")
else()
    file(REMOVE "${manifest}")
endif()
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "installing ${BUILD} into ${STAGE} failed (${rc})")
endif()
