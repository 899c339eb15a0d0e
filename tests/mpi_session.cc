// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Tests of SerialMpiSession}
//
// The test executable's main() (tests/test_main.cc) creates a
// SerialMpiSession before MPI_Init, as the program does. These tests check
// that Open MPI took the private directory (its session files are in it,
// so two runs at once cannot share them), that a directory the user set is
// kept, and that the object removes the directory it made.

// Not typed on the dimension: the MPI environment of a process.

#include <core/mpi_session.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>

namespace
{
  using namespace SoftRobot;
  namespace fs = std::filesystem;

  // Sets an environment variable for the life of the object and restores
  // it (or its absence) afterwards.
  class ScopedVariable
  {
  public:
    ScopedVariable(const char *name, const char *value)
      : name(name)
    {
      const char *old = std::getenv(name);
      had_value       = (old != nullptr);
      if (had_value)
        old_value = old;
      if (value != nullptr)
        setenv(name, value, 1);
      else
        unsetenv(name);
    }
    ~ScopedVariable()
    {
      if (had_value)
        setenv(name.c_str(), old_value.c_str(), 1);
      else
        unsetenv(name.c_str());
    }

  private:
    std::string name;
    bool        had_value = false;
    std::string old_value;
  };

  bool
  under_mpirun()
  {
    return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr;
  }
} // namespace



// This process runs without mpirun (as ctest starts it): its session
// directory base is a private directory named by SerialMpiSession, and Open
// MPI's session files for this process (ompi.<host>.<uid>) are inside it.
TEST(SerialMpiSession, OpenMpiUsesThePrivateDirectory)
{
  if (under_mpirun())
    GTEST_SKIP() << "started by mpirun";
  const char *base = std::getenv("OMPI_MCA_orte_tmpdir_base");
  ASSERT_NE(base, nullptr);
  const fs::path directory(base);
  EXPECT_EQ(directory.filename().string().rfind("soft-robot-mpi-", 0), 0u)
    << directory;
  ASSERT_TRUE(fs::is_directory(directory)) << directory;
  bool has_session_files = false;
  for (const auto &entry : fs::directory_iterator(directory))
    if (entry.is_directory() &&
        entry.path().filename().string().rfind("ompi.", 0) == 0)
      has_session_files = true;
  EXPECT_TRUE(has_session_files)
    << "no ompi.* session directory in " << directory;
  EXPECT_STREQ(std::getenv("OMPI_MCA_ess_singleton_isolated"), "1");
}



// A session directory base that the user set is kept, and no directory is
// made.
TEST(SerialMpiSession, KeepsTheUsersDirectory)
{
  if (under_mpirun())
    GTEST_SKIP() << "started by mpirun";
  const ScopedVariable   user("OMPI_MCA_orte_tmpdir_base", "/users/choice");
  const SerialMpiSession session;
  EXPECT_TRUE(session.session_directory().empty());
  EXPECT_STREQ(std::getenv("OMPI_MCA_orte_tmpdir_base"), "/users/choice");
}



// Without a setting, the object makes a new directory under TMPDIR, names
// it in OMPI_MCA_orte_tmpdir_base, and removes it, with what Open MPI left
// in it, when it is destroyed.
TEST(SerialMpiSession, MakesAndRemovesItsDirectory)
{
  if (under_mpirun())
    GTEST_SKIP() << "started by mpirun";
  const fs::path temporary = fs::temp_directory_path() / "mpi_session_test";
  fs::remove_all(temporary);
  fs::create_directories(temporary);
  const ScopedVariable tmpdir("TMPDIR", temporary.c_str());
  const ScopedVariable unset("OMPI_MCA_orte_tmpdir_base", nullptr);
  fs::path             made;
  {
    const SerialMpiSession session;
    made = session.session_directory();
    ASSERT_FALSE(made.empty());
    EXPECT_EQ(made.parent_path(), temporary);
    EXPECT_TRUE(fs::is_directory(made));
    EXPECT_EQ(made.string(), std::getenv("OMPI_MCA_orte_tmpdir_base"));
    fs::create_directories(made / "ompi.host.0" / "jf.0");
    std::ofstream(made / "ompi.host.0" / "jf.0" / "left-over") << "x";
  }
  EXPECT_FALSE(fs::exists(made));
  fs::remove_all(temporary);
}
