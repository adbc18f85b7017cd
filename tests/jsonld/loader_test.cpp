#include "jsonld/loader.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;
using mospec::Error;
using mospec::SourceLoc;
using mospec::jsonld::MappedDocumentLoader;

namespace {

class LoaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() /
        ("mospec-loader-test-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "meta" / "geometry");
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& rel, const std::string& text) {
    fs::path p = dir_ / rel;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p.string();
  }
  std::string dir(const std::string& rel = {}) const { return (dir_ / rel).string(); }

  fs::path dir_;
};

TEST_F(LoaderTest, LongestPrefixWins) {
  MappedDocumentLoader loader;
  loader.map("https://example.org/", "/a");
  loader.map("https://example.org/meta/", "/b/");
  EXPECT_EQ(loader.resolve("https://example.org/x.json"), "/a/x.json");
  EXPECT_EQ(loader.resolve("https://example.org/meta/geometry/c.json"), "/b/geometry/c.json");
  EXPECT_EQ(loader.resolve("https://example.org/meta/c.json#frag"), "/b/c.json");
  EXPECT_EQ(loader.resolve("https://other.org/x.json"), "");
}

TEST_F(LoaderTest, FallbacksApplyOnlyWhereNoMappingDoes) {
  MappedDocumentLoader loader;
  loader.map_fallback("https://example.org/meta/", "/builtin");
  EXPECT_EQ(loader.resolve("https://example.org/meta/c.json"), "/builtin/c.json");
  // A user's mapping of a parent prefix beats a longer fallback: an app that
  // maps the metamodels elsewhere keeps its own files.
  loader.map("https://example.org/", "/user");
  EXPECT_EQ(loader.resolve("https://example.org/meta/c.json"), "/user/meta/c.json");
  EXPECT_EQ(loader.resolve("https://other.org/x.json"), "");
}

TEST_F(LoaderTest, FileIrisAndPlainPaths) {
  MappedDocumentLoader loader;
  EXPECT_EQ(loader.resolve("file:///tmp/a%20b.json"), "/tmp/a b.json");
  EXPECT_EQ(loader.resolve("file://localhost/tmp/a.json"), "/tmp/a.json");
  EXPECT_EQ(loader.resolve("models/a.json"), "models/a.json");
  EXPECT_EQ(loader.resolve("/abs/a.json"), "/abs/a.json");
  EXPECT_EQ(loader.resolve("tag:non-dereferencable-iri"), "");
}

TEST_F(LoaderTest, ParsesEachFileOnce) {
  write("meta/geometry/c.json", R"({"@context": {"x": "http://x/"}})");
  MappedDocumentLoader loader;
  loader.map("https://example.org/meta/", dir("meta"));
  auto a = loader.load("https://example.org/meta/geometry/c.json", {}, true);
  auto b = loader.load("https://example.org/meta/geometry/c.json", {}, true);
  auto c = loader.load_file(dir("meta/geometry/../geometry/c.json"));
  EXPECT_EQ(loader.documents_read(), 1u);
  EXPECT_EQ(a.document, b.document);
  EXPECT_EQ(a.document, c.document);
  EXPECT_EQ(a.document_url, "https://example.org/meta/geometry/c.json");
  EXPECT_TRUE(c.document_url.starts_with("file:///")) << c.document_url;
  ASSERT_NE(a.file_id, 0u);
  EXPECT_EQ(loader.files().path(a.file_id), dir("meta/geometry/c.json"));
  // Locations inside the document name the file.
  ASSERT_TRUE(a.document->is_object());
  SourceLoc loc = a.document->get("@context")->location();
  EXPECT_EQ(loc.file, a.file_id);
  EXPECT_EQ(loc.line, 1u);
  EXPECT_EQ(loc.column, 14u);
}

// The documents of a load are read on two threads: both get the same parsed
// document and file id for a file, whichever reads it first, and a file read
// by both counts once.
TEST_F(LoaderTest, TwoThreadsLoadingTheSameFilesAgree) {
  constexpr int kFiles = 40;
  for (int i = 0; i < kFiles; ++i) {
    write("meta/f" + std::to_string(i) + ".json",
          R"({"@context": {"x": "http://x/)" + std::to_string(i) + R"("}})");
  }
  MappedDocumentLoader loader;
  loader.map("https://example.org/meta/", dir("meta"));
  std::vector<mospec::jsonld::RemoteDocument> got[2];
  auto work = [&](int t) {
    for (int i = 0; i < kFiles; ++i) {
      // One thread from the front, the other from the back: they meet.
      const int f = t == 0 ? i : kFiles - 1 - i;
      got[t].push_back(
          loader.load("https://example.org/meta/f" + std::to_string(f) + ".json", {}, true));
    }
  };
  std::thread other(work, 1);
  work(0);
  other.join();
  for (int i = 0; i < kFiles; ++i) {
    const auto& a = got[0][static_cast<size_t>(i)];
    const auto& b = got[1][static_cast<size_t>(kFiles - 1 - i)];
    EXPECT_EQ(a.document, b.document) << i;
    EXPECT_EQ(a.file_id, b.file_id) << i;
    EXPECT_EQ(loader.files().path(a.file_id), dir("meta/f" + std::to_string(i) + ".json"));
  }
  EXPECT_EQ(loader.documents_read(), static_cast<size_t>(kFiles));
}

// The loader reads every document into one buffer: a document read after a
// larger one is parsed from its own bytes only, never from what the larger
// one left behind.
TEST_F(LoaderTest, EachDocumentIsParsedFromItsOwnBytes) {
  std::string big = "{\"a\": [";
  for (int i = 0; i < 2000; ++i) big += std::to_string(i) + ", ";
  big += "0]}";
  write("big.json", big);
  write("small.json", R"({"b": 1})");
  // Valid only if the big document's bytes followed it; alone it ends early.
  const std::string cut = write("cut.json", R"({"c": [1, 2)");
  MappedDocumentLoader loader;
  loader.map("https://example.org/", dir());
  auto a = loader.load("https://example.org/big.json", {}, false);
  auto b = loader.load("https://example.org/small.json", {}, false);
  ASSERT_TRUE(a.document->is_object());
  EXPECT_EQ(a.document->get("a")->as_array().size(), 2001u);
  ASSERT_TRUE(b.document->is_object());
  EXPECT_EQ(b.document->as_object().size(), 1u);
  EXPECT_EQ(b.document->get("b")->as_number(), 1);
  try {
    loader.load("https://example.org/cut.json", {}, false);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "invalid json");
    EXPECT_EQ(e.diagnostic().file, cut);
    EXPECT_EQ(e.diagnostic().line, 1u);
  }
  // The first document is unchanged by the reads after it.
  EXPECT_EQ(a.document->get("a")->as_array().back().as_number(), 0);
}

TEST_F(LoaderTest, UnmappedIriNamesIriAndReference) {
  std::string app = write("a.json", "{\n  \"@context\": [\n    \"https://x/y.json\"]}");
  MappedDocumentLoader loader;
  loader.map("https://comp-rob2b.github.io/", dir("meta"));
  auto doc = loader.load_file(app);
  SourceLoc ref = doc.document->get("@context")->as_array()[0].location();
  try {
    loader.load("https://x/y.json", ref, true);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "loading remote context failed");
    EXPECT_EQ(std::string(e.what()),
              app +
                  ":3:5: error: cannot load remote context <https://x/y.json>: no --map or "
                  "iri-map entry maps this IRI (known prefixes: https://comp-rob2b.github.io/)");
  }
  try {
    loader.load("https://x/y.json", ref, false);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "loading document failed");
    EXPECT_NE(std::string(e.what()).find("cannot load document <https://x/y.json>"),
              std::string::npos);
  }
}

TEST_F(LoaderTest, MissingFileNamesPathAndReason) {
  MappedDocumentLoader loader;
  loader.map("https://example.org/", dir());
  try {
    loader.load("https://example.org/missing.json", {}, true);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "loading remote context failed");
    std::string what = e.what();
    EXPECT_NE(what.find("<https://example.org/missing.json>"), std::string::npos) << what;
    EXPECT_NE(what.find(dir("missing.json")), std::string::npos) << what;
    EXPECT_NE(what.find("No such file or directory"), std::string::npos) << what;
  }
  EXPECT_THROW(
      {
        try {
          loader.load_file(dir("meta"));  // a directory
        } catch (const Error& e) {
          EXPECT_EQ(e.code(), "loading document failed");
          EXPECT_NE(std::string(e.what()).find("Is a directory"), std::string::npos);
          throw;
        }
      },
      Error);
}

TEST_F(LoaderTest, RefusesDevices) {
  MappedDocumentLoader loader;
  try {
    loader.load("file:///dev/zero", {}, true);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "loading remote context failed");
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
  }
}

TEST_F(LoaderTest, JsonSyntaxErrorsKeepTheirLocation) {
  std::string bad = write("bad.json", "{\n  \"a\": [1,\n}");
  MappedDocumentLoader loader;
  loader.map("https://example.org/", dir());
  try {
    loader.load("https://example.org/bad.json", {}, false);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "invalid json");
    EXPECT_EQ(e.diagnostic().file, bad);
    EXPECT_EQ(e.diagnostic().line, 3u);
  }
}

// ---- the sandbox ------------------------------------------------------------

// A confined loader over dir()/tree, with a secret beside the tree.
class SandboxTest : public LoaderTest {
 protected:
  void SetUp() override {
    LoaderTest::SetUp();
    write("tree/ok.json", R"({"@context": {"x": "http://x/"}})");
    write("secret.json", R"({"@context": {"TOPSECRET": "http://x/"}})");
    write("tree2/ok.json", R"({"@context": {"TOPSECRET": "http://x/"}})");
    fs::create_symlink(dir("secret.json"), dir("tree/link.json"));
    fs::create_directories(dir("tree/sub"));
    fs::create_directory_symlink(dir(), dir("tree/sub/up"));
    app_ = write("tree/app.json", "{\n  \"@context\": [\n    \"x\"]}");
    loader_.map("https://ex.org/", dir("tree"));
    loader_.confine();
    ref_ = loader_.load_file(app_).document->get("@context")->as_array()[0].location();
  }
  // The error of loading `iri` as a context from app.json:3:5.
  std::string error_of(const std::string& iri) {
    try {
      loader_.load(iri, ref_, true);
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), "loading remote context failed");
      EXPECT_EQ(e.diagnostic().file, app_);
      EXPECT_EQ(e.diagnostic().line, 3u);
      std::string what = e.what();
      EXPECT_EQ(what.find("TOPSECRET"), std::string::npos) << what;
      return what;
    }
    ADD_FAILURE() << iri << " loaded";
    return {};
  }
  std::string outside(const std::string& iri, const std::string& resolved) {
    return app_ + ":3:5: error: cannot load remote context <" + iri + ">: it resolves to '" +
           resolved + "', outside the model tree";
  }

  MappedDocumentLoader loader_;
  std::string app_;
  SourceLoc ref_;
};

TEST_F(SandboxTest, LoadsInsideTheTree) {
  EXPECT_NO_THROW(loader_.load("https://ex.org/ok.json", ref_, true));
  EXPECT_NO_THROW(loader_.load("https://ex.org/sub/../ok.json", ref_, true));
  EXPECT_NO_THROW(
      loader_.load("file://" + fs::canonical(dir("tree/ok.json")).string(), ref_, true));
}

TEST_F(SandboxTest, RefusesEveryWayOut) {
  const std::string secret = fs::canonical(dir("secret.json")).string();
  for (const std::string& iri : std::vector<std::string>{
           "https://ex.org/../secret.json", "https://ex.org/%2e%2e/secret.json",
           "https://ex.org/%2E%2E%2Fsecret.json", "https://ex.org/link.json",
           "https://ex.org/sub/up/secret.json", "file://" + secret}) {
    std::string what = error_of(iri);
    EXPECT_EQ(what.substr(0, outside(iri, secret).size()), outside(iri, secret)) << what;
  }
  // A sibling whose name starts like the tree's is not inside it.
  const std::string sibling = fs::canonical(dir("tree2/ok.json")).string();
  EXPECT_EQ(error_of("file://" + sibling).substr(0, outside("file://" + sibling, sibling).size()),
            outside("file://" + sibling, sibling));
  // Plain absolute paths and devices: refused before anything is opened.
  EXPECT_NE(error_of("file:///etc/passwd").find("outside the model tree"), std::string::npos);
  EXPECT_NE(error_of("file:///proc/self/environ").find("outside the model tree"),
            std::string::npos);
  EXPECT_NE(error_of("file:///dev/zero").find("outside the model tree"), std::string::npos);
  EXPECT_EQ(loader_.documents_read(), 1u);  // app.json only
}

// The loader remembers each directory's canonical form (a document that is
// not a link is its directory's canonical path plus its name): a link beside
// documents already loaded, or a linked directory, is still resolved and
// refused.
TEST_F(SandboxTest, RememberedDirectoriesStillResolveLinks) {
  const std::string secret = fs::canonical(dir("secret.json")).string();
  EXPECT_NO_THROW(loader_.load("https://ex.org/ok.json", ref_, true));
  write("tree/sub/inside.json", R"({"@context": {}})");
  EXPECT_NO_THROW(loader_.load("https://ex.org/sub/inside.json", ref_, true));
  for (const std::string& iri :
       std::vector<std::string>{"https://ex.org/link.json", "https://ex.org/sub/up/secret.json",
                                "https://ex.org/sub/../link.json"}) {
    std::string what = error_of(iri);
    EXPECT_EQ(what.substr(0, outside(iri, secret).size()), outside(iri, secret)) << what;
  }
  EXPECT_EQ(loader_.documents_read(), 3u);  // app.json, ok.json, inside.json
}

TEST_F(SandboxTest, AllowedDirectoriesAndFallbacksCount) {
  const std::string sibling = "file://" + fs::canonical(dir("tree2/ok.json")).string();
  loader_.allow(dir("tree2"));
  EXPECT_NO_THROW(loader_.load(sibling, ref_, true));
  loader_.map_fallback("https://meta.example/", dir("meta"));
  write("meta/m.json", R"({"@context": {}})");
  EXPECT_NO_THROW(loader_.load("https://meta.example/m.json", ref_, true));
}

// Roots spelled with a trailing '/' or as "/" itself still contain their files
// (the check compares paths by spelling first, by components otherwise).
TEST_F(SandboxTest, RootsWithATrailingSlashOrTheFileSystemRoot) {
  const std::string sibling = "file://" + fs::canonical(dir("tree2/ok.json")).string();
  loader_.allow(dir("tree2") + "/");
  EXPECT_NO_THROW(loader_.load(sibling, ref_, true));
  const std::string secret = "file://" + fs::canonical(dir("secret.json")).string();
  EXPECT_NE(error_of(secret).find("outside the model tree"), std::string::npos);
  loader_.allow("/");
  EXPECT_NO_THROW(loader_.load(secret, ref_, true));
}

TEST_F(SandboxTest, ControlCharactersAreRefusedRawOrEncoded) {
  EXPECT_EQ(error_of("https://ex.org/ok.json%00.txt"),
            app_ +
                ":3:5: error: cannot load remote context <https://ex.org/ok.json%00.txt>: the "
                "IRI contains the percent-encoded control character U+0000; IRIs that name "
                "files may not contain U+0000-U+001F or U+007F");
  EXPECT_NE(error_of("https://ex.org/ok%0a.json").find("control character U+000A"),
            std::string::npos);
  EXPECT_EQ(error_of(std::string("https://ex.org/ok\x01.json")),
            app_ +
                ":3:5: error: cannot load remote context <https://ex.org/ok\\x01.json>: the "
                "IRI contains the control character U+0001; IRIs that name files may not "
                "contain U+0000-U+001F or U+007F");
  // Unconfined too: a %00 would otherwise cut the path short.
  MappedDocumentLoader open;
  open.map("https://ex.org/", dir("tree"));
  EXPECT_THROW(open.load("https://ex.org/ok.json%00", {}, true), Error);
}

}  // namespace
