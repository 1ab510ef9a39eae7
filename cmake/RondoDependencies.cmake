# Every dependency is a Debian package that scripts/setup installs; nothing is downloaded here.
find_package(Threads REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(yaml-cpp REQUIRED)
find_package(date REQUIRED)           # Howard Hinnant's date/tz (libhowardhinnant-date-dev)
find_package(SQLiteCpp REQUIRED)      # libsqlitecpp-dev, over the system SQLite3
find_package(SQLite3 REQUIRED)
find_package(PostgreSQL REQUIRED)    # libpq-dev: the PostgreSQL store (rondo::store)
find_package(CLI11 REQUIRED)
find_package(fmt REQUIRED)
find_package(spdlog REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(HTTPLIB REQUIRED IMPORTED_TARGET cpp-httplib)  # libcpp-httplib-dev, rondo::service
find_package(PahoMqttCpp REQUIRED)  # libpaho-mqttpp-dev (with libpaho-mqtt-dev), rondo::vda5050
if(RONDO_BUILD_TESTS)
  find_package(GTest REQUIRED)
  find_package(rapidcheck REQUIRED)
endif()
if(RONDO_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()
