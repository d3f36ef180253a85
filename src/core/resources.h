// Where the project's data files (xsd/, xslt/, mappings/, docs/) are found at run time.
//
// The data folder is chosen once per process, the first of:
//   1. <executable dir>/../share/surrogate: an installed or unpacked package (`dpkg -x` into any
//      folder), or a copy of the install tree, wherever it was moved;
//   2. the source tree the program was built from, only for a program that still lies inside
//      its build folder (a build, and the tests, work without installing);
//   3. <install prefix>/share/surrogate, as configured (CMAKE_INSTALL_PREFIX).
// Every data file the program reads (the list is resources_manifest.cpp, made by CMake from the
// same list the install rules use) must be in that folder: one of them missing is an installation
// to repair, exit 1 "reinstall Surrogate: FILE is missing", never taken from another folder
// (an older installation's schemas beside a newer program would be wrong silently).
// $SURROGATE_RESOURCES, when set, is looked in first, file by file (a stylesheet under test).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace surrogate {

std::filesystem::path resourcePath(const std::string& relative);

// The data folder in use, after checking that every data file is in it; throws
// Error(Input, "", "installation", "reinstall Surrogate: FILE is missing ...") if not.
std::filesystem::path requireDataFiles();

// The data files the program reads, relative to the data folder (CMake's SURROGATE_DATA_FILES).
const std::vector<std::string>& dataFileNames();

}  // namespace surrogate
