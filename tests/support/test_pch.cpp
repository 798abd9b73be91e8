// The object the shared test precompiled header is built with (tests/CMakeLists.txt).
