// Confinement of gmsh's process by the kernel (Linux Landlock, kernel 5.13 or later, no
// privileges needed): whatever a .geo asks gmsh to do, the process may afterwards
//  - create, write, truncate, rename and delete files only inside its own temporary folder;
//  - read only the files the .geo screen read (the mesh file, the files it includes or
//    merges, its .opt file) and the system's libraries (/usr, /lib*, /etc/ld.so.cache),
//    and execute nothing but those libraries;
//  - (kernel ABI 4 or later) neither connect nor bind TCP sockets; (ABI 6 or later)
//    neither reach abstract UNIX sockets nor signal processes outside itself.
// Access rights the kernel does not know are left out (an older kernel confines less,
// never nothing); where the kernel has no Landlock the process runs unconfined and the
// .geo screen (mesh/GeoScreen.hpp) is the only guard: the caller says so in the log.
#pragma once
#include <string>
#include <vector>

namespace stentor {

// The Landlock ABI version of the running kernel, 0 when it has none.
int landlock_abi();

// Confines this process as above, for good (it cannot be undone). Returns "" when done,
// else why it was not ("this kernel has no Landlock", a failed system call).
// Test hook: STENTOR_TEST_NO_LANDLOCK=1 leaves the process unconfined (tests/cli/geo_confine.sh).
std::string confine_process(const std::string& write_dir, const std::vector<std::string>& read_files);

}  // namespace stentor
