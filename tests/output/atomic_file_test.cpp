#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "rktsph/core/error.hpp"
#include "rktsph/output/atomic_file.hpp"

namespace rktsph::atomic_file_test {
namespace {

namespace fs = std::filesystem;

std::string read_whole_file(const fs::path& path) {
  std::ifstream stream(path, std::ios::binary);
  std::ostringstream content;
  content << stream.rdbuf();
  return content.str();
}

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() /
                 ("rktsph_atomic_test_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(directory_);
    fs::create_directories(directory_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(directory_, ignored);
  }

  std::size_t file_count() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(directory_), {}));
  }

  fs::path directory_;
};

TEST_F(AtomicFileTest, WritesAndReplacesContent) {
  const fs::path file = directory_ / "summary.json";
  write_file_atomically(file, std::string("first\n"));
  EXPECT_EQ(read_whole_file(file), "first\n");
  write_file_atomically(file, [](std::ostream& out) { out << "second " << 2 << '\n'; });
  EXPECT_EQ(read_whole_file(file), "second 2\n");
  EXPECT_EQ(file_count(), 1u);  // no temporary left behind
}

TEST_F(AtomicFileTest, BinaryContentIsWrittenUnchanged) {
  const std::string content("a\0b\r\n\xff", 6);
  const fs::path file = directory_ / "binary";
  write_file_atomically(file, content);
  EXPECT_EQ(read_whole_file(file), content);
}

TEST_F(AtomicFileTest, TemporaryIsInTheSameDirectoryAndNamedAfterThePid) {
  const fs::path file = directory_ / "a.csv";
  const fs::path temporary = temporary_path_for(file);
  EXPECT_EQ(temporary.parent_path(), file.parent_path());
  EXPECT_EQ(temporary.filename().string(), "a.csv.tmp-" + std::to_string(::getpid()));
}

TEST_F(AtomicFileTest, MissingDirectoryThrowsRunErrorNamingThePathAndLeavesNothing) {
  const fs::path missing_directory = directory_ / "does_not_exist";
  const fs::path file = missing_directory / "out.vtu";
  try {
    write_file_atomically(file, std::string("x"));
    FAIL() << "expected RunError";
  } catch (const RunError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(missing_directory.string()), std::string::npos) << message;
    EXPECT_NE(message.find("No such file or directory"), std::string::npos) << message;
  }
  EXPECT_FALSE(fs::exists(missing_directory));
  EXPECT_FALSE(fs::exists(temporary_path_for(file)));
  EXPECT_EQ(file_count(), 0u);
}

TEST_F(AtomicFileTest, ThrowingWriterKeepsPreviousContentAndRemovesTemporary) {
  const fs::path file = directory_ / "probes.csv";
  write_file_atomically(file, std::string("complete old content\n"));
  const auto failing_writer = [](std::ostream& out) {
    out << "partial new cont";
    out.flush();  // the partial text really reaches the temporary file before the failure
    throw std::runtime_error("simulated failure mid-write");
  };
  EXPECT_THROW(write_file_atomically(file, failing_writer), std::runtime_error);
  EXPECT_EQ(read_whole_file(file), "complete old content\n");
  EXPECT_FALSE(fs::exists(temporary_path_for(file)));
  EXPECT_EQ(file_count(), 1u);
}

TEST_F(AtomicFileTest, FailedStreamIsReportedAsRunError) {
  const fs::path file = directory_ / "state";
  const auto breaking_writer = [](std::ostream& out) { out.setstate(std::ios::badbit); };
  EXPECT_THROW(write_file_atomically(file, breaking_writer), RunError);
  EXPECT_FALSE(fs::exists(file));
  EXPECT_EQ(file_count(), 0u);
}

TEST_F(AtomicFileTest, RenameOntoADirectoryThrowsRunErrorAndCleansUp) {
  const fs::path target = directory_ / "occupied";
  fs::create_directories(target / "child");
  EXPECT_THROW(write_file_atomically(target, std::string("x")), RunError);
  EXPECT_TRUE(fs::is_directory(target));
  EXPECT_FALSE(fs::exists(temporary_path_for(target)));
}

TEST_F(AtomicFileTest, PlantedSymlinkAtTheTemporaryNameIsNotFollowed) {
  // Someone who can predict the temporary name plants a link to a file of theirs there.
  const fs::path victim = directory_ / "victim.txt";
  std::ofstream(victim) << "precious\n";
  const fs::path summary = directory_ / "summary.json";
  fs::create_symlink(victim, temporary_path_for(summary));
  write_file_atomically(summary, std::string("{}\n"));
  EXPECT_EQ(read_whole_file(victim), "precious\n");
  EXPECT_EQ(fs::symlink_status(summary).type(), fs::file_type::regular);
  EXPECT_EQ(read_whole_file(summary), "{}\n");
  // The planted link is left alone (a next run's stale-temporary sweep removes it).
  EXPECT_TRUE(fs::is_symlink(temporary_path_for(summary)));
}

TEST_F(AtomicFileTest, SymlinkAtTheDestinationIsReplacedNotWrittenThrough) {
  const fs::path victim = directory_ / "victim.txt";
  std::ofstream(victim) << "precious\n";
  const fs::path summary = directory_ / "summary.json";
  fs::create_symlink(victim, summary);
  write_file_atomically(summary, std::string("{}\n"));
  EXPECT_EQ(read_whole_file(victim), "precious\n");
  EXPECT_EQ(fs::symlink_status(summary).type(), fs::file_type::regular);
}

TEST_F(AtomicFileTest, TemporaryNamesAreRecognisedAndNothingElse) {
  EXPECT_TRUE(is_temporary_file_name(temporary_path_for(directory_ / "a.csv").filename().string()));
  EXPECT_TRUE(is_temporary_file_name("fields_000003.vtu.tmp-4242"));
  EXPECT_TRUE(is_temporary_file_name("summary.json.tmp-4242-7"));
  EXPECT_FALSE(is_temporary_file_name("summary.json"));
  EXPECT_FALSE(is_temporary_file_name("notes.tmp-draft"));
  EXPECT_FALSE(is_temporary_file_name(".tmp-12"));
  EXPECT_FALSE(is_temporary_file_name("a.tmp-"));
  EXPECT_FALSE(is_temporary_file_name("a.tmp-12-"));
}

// A full disk cannot be made in a test, but /dev/full fails every write with ENOSPC.
TEST_F(AtomicFileTest, FullDiskNamesThePathAndTheSystemReason) {
  const int descriptor = ::open("/dev/full", O_WRONLY | O_CLOEXEC);
  if (descriptor < 0) GTEST_SKIP() << "no /dev/full";
  const fs::path named = directory_ / "fields_000001.vtu";
  try {
    write_to_descriptor(descriptor, named, [](std::ostream& out) {
      for (int i = 0; i < 100000; ++i)
        out << "0123456789";
    });
    ADD_FAILURE() << "expected RunError";
  } catch (const RunError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(named.string()), std::string::npos) << message;
    EXPECT_NE(message.find("No space left on device"), std::string::npos) << message;
  }
  ::close(descriptor);
}

// A write the kernel refuses in the middle of a large file (here: beyond a file-size limit, in a
// child process) is reported with its reason; it used to come out as "unknown I/O error", and
// the previous complete file stays.
TEST_F(AtomicFileTest, RefusedWriteInALargeFileNamesTheSystemReasonAndKeepsTheOldFile) {
  const fs::path file = directory_ / "fields_000001.vtu";
  write_file_atomically(file, std::string("old\n"));
  int channel[2];
  ASSERT_EQ(::pipe(channel), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(channel[0]);
    std::signal(SIGXFSZ, SIG_IGN);  // the write then fails with EFBIG instead of killing
    const rlimit limit{64 * 1024, 64 * 1024};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    std::string message = "no error";
    try {
      write_file_atomically(file, [](std::ostream& out) {
        for (int i = 0; i < 100000; ++i)
          out << "0123456789";
      });
    } catch (const RunError& error) {
      message = error.what();
    }
    [[maybe_unused]] const ssize_t written = ::write(channel[1], message.data(), message.size());
    ::_exit(0);
  }
  ::close(channel[1]);
  std::string message;
  char buffer[512];
  for (ssize_t count; (count = ::read(channel[0], buffer, sizeof buffer)) > 0;)
    message.append(buffer, static_cast<std::size_t>(count));
  ::close(channel[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
  EXPECT_NE(message.find("File too large"), std::string::npos) << message;
  EXPECT_EQ(read_whole_file(file), "old\n");
  EXPECT_EQ(file_count(), 1u);
}

}  // namespace
}  // namespace rktsph::atomic_file_test
