# Installs the built project into a fresh prefix, then configures, builds and runs the consumer
# against it with find_package(fastcorot). Variables: BUILD_DIR, SOURCE_DIR, WORK_DIR, and
# CONSUMER_FLAGS (the sanitizer flags of an instrumented build, which its users compile with).
file(REMOVE_RECURSE "${WORK_DIR}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${WORK_DIR}/prefix"
                RESULT_VARIABLE status)
if(status)
  message(FATAL_ERROR "cmake --install failed")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${WORK_DIR}/build"
                        -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release
                        "-DCMAKE_CXX_FLAGS=${CONSUMER_FLAGS}"
                RESULT_VARIABLE status)
if(status)
  message(FATAL_ERROR "configuring the consumer with find_package(fastcorot) failed")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" --build "${WORK_DIR}/build" RESULT_VARIABLE status)
if(status)
  message(FATAL_ERROR "building the consumer failed")
endif()
execute_process(COMMAND "${WORK_DIR}/build/consumer" RESULT_VARIABLE status)
if(status)
  message(FATAL_ERROR "the consumer's check failed")
endif()
