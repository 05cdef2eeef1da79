// Shell words (shell_quote.h): hostile strings go through a real /bin/sh and come back as they were,
// as one argument each, and run nothing.
#include "util/shell_quote.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "util/child_process.h"

namespace ra::util {
namespace {

// What /bin/sh makes of `command_text`: printf %s of each of its words, NUL after each.
std::string through_sh(const std::string& words) {
  ChildSpec spec;
  spec.argv = {"/bin/sh", "-c", "printf '%s\\0' " + words};
  spec.capture_output = true;
  spec.stdin_null = true;
  const ProgramResult r = run_program(spec);
  EXPECT_TRUE(r.exited_ok()) << r.output;
  return r.output;
}

const std::string kPwned = "/tmp/renderaudit-shell-quote-test-" + std::to_string(::getpid());

std::vector<std::string> hostile_words() {
  return {"plain",
          "",
          "src dir $(touch " + kPwned + ")",
          "`touch " + kPwned + "`",
          "it's",
          "''",
          "'",
          "a\nb\n",
          "semi; touch " + kPwned,
          "a && b || c | d > e < f",
          "$HOME ${HOME} $((1+1))",
          "*",
          "~",
          "~/x",
          "#not a comment",
          "\\ back\\slash\\",
          "\"double\"",
          "tab\there",
          "!bang",
          "-n",
          "--out=x y",
          "x=1",
          "\x01\x7f\xc3\xa9"};
}

TEST(ShellQuote, HostileWordsComeBackAsTheyWereAndRunNothing) {
  std::filesystem::remove(kPwned);
  for (const std::string& w : hostile_words()) {
    EXPECT_EQ(through_sh(shell_quote(w)), w + std::string(1, '\0')) << shell_quote(w);
  }
  std::string all, expected;
  for (const std::string& w : hostile_words()) {
    all += " " + shell_quote(w);
    expected += w + std::string(1, '\0');
  }
  EXPECT_EQ(through_sh(all), expected);
  EXPECT_FALSE(std::filesystem::exists(kPwned)) << "a quoted word ran a command";
}

TEST(ShellQuote, SafeWordsStayBare) {
  EXPECT_EQ(shell_quote("/usr/bin/llvm-config-15"), "/usr/bin/llvm-config-15");
  EXPECT_EQ(shell_quote("-Dgallium-drivers=llvmpipe,softpipe"),
            "-Dgallium-drivers=llvmpipe,softpipe");
  EXPECT_EQ(shell_quote("egl-llvmpipe@backports"), "egl-llvmpipe@backports");
  EXPECT_EQ(shell_quote("a b"), "'a b'");
  EXPECT_EQ(shell_quote("it's"), "'it'\\''s'");
  EXPECT_EQ(shell_quote(""), "''");
  EXPECT_EQ(shell_quote("~"), "'~'");
}

TEST(ShellQuote, ACommandIsItsWordsAndAnAssignmentFirstIsQuoted) {
  EXPECT_EQ(shell_command({"cc", "a b.c", "-o", "x"}), "cc 'a b.c' -o x");
  EXPECT_EQ(shell_command({"X=1", "y=2"}), "'X=1' y=2");
  EXPECT_EQ(through_sh(shell_command({"a b", "c'd", "$(e)"})), std::string("a b\0c'd\0$(e)\0", 13));
}

}  // namespace
}  // namespace ra::util
