#include "jsonld/loader.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cassert>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <memory_resource>
#include <mutex>
#include <new>
#include <system_error>
#include <vector>

#include "support/arena.hpp"
#include "support/io.hpp"
#include "support/paths.hpp"

namespace mospec::jsonld {

namespace {

// A parsed document and the arena its values live in. The tree is in the
// arena whole (the parser builds every string, array, object and key index
// there; json::lives_in), so it is dropped with the arena and never destroyed
// value by value.
struct ParsedDocument {
  // Parsed values take about three times the bytes of their text (2.9 over
  // the shipped models, robots and metamodels, 4.1 at most), so the first
  // block holds most documents; the arena grows past it by itself.
  explicit ParsedDocument(size_t text_bytes) : arena(std::max<size_t>(1024, 3 * text_bytes)) {}
  Arena arena;
  const json::Value* root = nullptr;  // in the arena
};

}  // namespace
namespace fs = std::filesystem;

namespace {

constexpr std::string_view kContextFailed = "loading remote context failed";
constexpr std::string_view kDocumentFailed = "loading document failed";

bool is_alpha(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}

// RFC 3986 scheme: ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":". Anything
// else is taken as a local path, so "models/a.json" and "/abs/a.json" load as is.
bool has_scheme(std::string_view s) {
  if (s.empty() || !is_alpha(s[0])) return false;
  for (size_t i = 1; i < s.size(); ++i) {
    char c = s[i];
    if (c == ':') return true;
    if (!is_alpha(c) && !(c >= '0' && c <= '9') && c != '+' && c != '-' && c != '.') return false;
  }
  return false;
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// IRIs percent-encode characters that file names may contain literally (spaces).
std::string percent_decode(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size()) {
      int hi = hex_value(s[i + 1]);
      int lo = hex_value(s[i + 2]);
      if (hi >= 0 && lo >= 0) {
        out += static_cast<char>(hi * 16 + lo);
        i += 2;
        continue;
      }
    }
    out += s[i];
  }
  return out;
}

// Query and fragment name parts of a web resource, never of the file behind it.
std::string_view strip_query_fragment(std::string_view iri) {
  size_t cut = iri.find_first_of("?#");
  return cut == std::string_view::npos ? iri : iri.substr(0, cut);
}

std::string file_url(const std::string& canonical) {
  static constexpr std::string_view kUnsafe = " %\"<>\\^`{|}#?";
  std::string out = "file://";
  for (char c : canonical) {
    auto u = static_cast<unsigned char>(c);
    if (u < 0x21 || kUnsafe.find(c) != std::string_view::npos) {
      static constexpr char kHex[] = "0123456789ABCDEF";
      out += '%';
      out += kHex[u >> 4];
      out += kHex[u & 15];
    } else {
      out += c;
    }
  }
  return out;
}

// The first control character (U+0000-U+001F, U+007F) in `s`, or -1.
int control_character(std::string_view s) {
  for (char c : s) {
    auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) return u;
  }
  return -1;
}

std::string code_point(int u) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string out = "U+00";
  out += kHex[(u >> 4) & 15];
  out += kHex[u & 15];
  return out;
}

}  // namespace

struct MappedDocumentLoader::Sync {
  std::mutex mutex;
  // The texts of documents being parsed, each reused across documents: the
  // parsed values copy what they keep, and a buffer sized for the largest
  // file saves an allocation (and the allocator's consolidation of freed
  // small blocks that a large request triggers) per document. With each, the
  // parser's scratch buffers, reused likewise. One per thread parsing at once.
  struct Buffers {
    std::string text;
    std::unique_ptr<json::ParseScratch> scratch;
  };
  std::vector<Buffers> read_buffers;
};

MappedDocumentLoader::MappedDocumentLoader() : sync_(std::make_unique<Sync>()) {}
MappedDocumentLoader::~MappedDocumentLoader() = default;
MappedDocumentLoader::MappedDocumentLoader(MappedDocumentLoader&&) noexcept = default;
MappedDocumentLoader& MappedDocumentLoader::operator=(MappedDocumentLoader&&) noexcept = default;

void MappedDocumentLoader::add_root(const std::string& dir) {
  if (!root_paths_.contains(dir)) {
    root_paths_.emplace(dir, canonical_.canonical(dir.empty() ? "." : dir));
  }
}

void MappedDocumentLoader::map(std::string prefix, std::string dir) {
  while (dir.size() > 1 && dir.back() == '/') dir.pop_back();
  std::lock_guard lock(sync_->mutex);
  add_root(dir);
  prefixes_[std::move(prefix)] = std::move(dir);
}

void MappedDocumentLoader::map_fallback(std::string prefix, std::string dir) {
  while (dir.size() > 1 && dir.back() == '/') dir.pop_back();
  std::lock_guard lock(sync_->mutex);
  add_root(dir);
  fallbacks_[std::move(prefix)] = std::move(dir);
}

void MappedDocumentLoader::allow(std::string dir) {
  std::lock_guard lock(sync_->mutex);
  add_root(dir);
  allowed_.push_back(std::move(dir));
}

void MappedDocumentLoader::confine(bool on) {
  std::lock_guard lock(sync_->mutex);
  confined_ = on;
}

bool MappedDocumentLoader::confined() const {
  std::lock_guard lock(sync_->mutex);
  return confined_;
}

size_t MappedDocumentLoader::documents_read() const {
  std::lock_guard lock(sync_->mutex);
  return reads_;
}

std::string MappedDocumentLoader::canonical(std::string_view path) const {
  std::lock_guard lock(sync_->mutex);
  return canonical_.canonical(path);
}

namespace {

// Whether `path` is `root` or lies below it, by their spelling: true only when
// is_within(path, root) is (root is an absolute path without a trailing '/'
// and `path` continues it at a '/'), so a false answer is checked again by
// is_within. Both are canonical paths, so this answers nearly every check
// without building std::filesystem paths.
bool plainly_within(std::string_view path, std::string_view root) {
  if (root == "/") return path.starts_with('/');
  if (root.size() < 2 || root[0] != '/' || root[1] == '/' || root.back() == '/') return false;
  return path.starts_with(root) && (path.size() == root.size() || path[root.size()] == '/');
}

}  // namespace

bool MappedDocumentLoader::inside_sandbox(const std::string& canonical) const {
  // Any root will do: first by spelling, then component by component.
  auto any_root = [this](const auto& within) {
    for (const auto* table : {&prefixes_, &fallbacks_}) {
      for (const auto& entry : *table) {
        if (within(root_paths_.at(entry.second))) return true;
      }
    }
    for (const std::string& dir : allowed_) {
      if (within(root_paths_.at(dir))) return true;
    }
    return false;
  };
  if (any_root([&canonical](const std::string& root) { return plainly_within(canonical, root); }))
    return true;
  const fs::path p(canonical);
  return any_root([&p](const std::string& root) { return is_within(p, fs::path(root)); });
}

std::string MappedDocumentLoader::sandbox_roots() const {
  std::vector<std::string> roots;
  for (const auto* table : {&prefixes_, &fallbacks_}) {
    for (const auto& entry : *table) roots.push_back(canonical_path(entry.second).string());
  }
  for (const std::string& dir : allowed_) roots.push_back(canonical_path(dir).string());
  std::sort(roots.begin(), roots.end());
  roots.erase(std::unique(roots.begin(), roots.end()), roots.end());
  std::string out;
  for (const std::string& r : roots) out.append(out.empty() ? "" : ", ").append(escaped_bytes(r));
  return out.empty() ? "none" : out;
}

std::string MappedDocumentLoader::resolve_for_loading(std::string_view iri,
                                                      SourceLoc referenced_from,
                                                      std::string_view code,
                                                      std::string_view what) const {
  std::lock_guard lock(sync_->mutex);
  return resolve_for_loading_locked(iri, referenced_from, code, what, nullptr);
}

std::string MappedDocumentLoader::resolve_for_loading_locked(std::string_view iri,
                                                             SourceLoc referenced_from,
                                                             std::string_view code,
                                                             std::string_view what,
                                                             std::string* mapped) const {
  const std::string& ref_file = files_.path(referenced_from.file);
  auto fail = [&](const std::string& reason) -> Error {
    return Error(std::string(code),
                 "cannot load " + std::string(what) + " <" + escaped_bytes(iri) + ">: " + reason,
                 ref_file, referenced_from.line, referenced_from.column);
  };
  if (int c = control_character(iri); c >= 0) {
    throw fail("the IRI contains the control character " + code_point(c) +
               "; IRIs that name files may not contain U+0000-U+001F or U+007F");
  }
  std::string path = resolve_locked(iri);
  if (path.empty()) {
    std::string known;
    for (const auto& entry : prefixes_) {
      if (!known.empty()) known += ", ";
      known += entry.first;
    }
    if (known.empty()) known = "none";
    throw fail("no --map or iri-map entry maps this IRI (known prefixes: " + known + ")");
  }
  if (int c = control_character(path); c >= 0) {
    throw fail("the IRI contains the percent-encoded control character " + code_point(c) +
               "; IRIs that name files may not contain U+0000-U+001F or U+007F");
  }
  if (confined_) {
    const std::string canonical = canonical_.canonical(path);
    if (!inside_sandbox(canonical)) {
      throw fail("it resolves to '" + escaped_bytes(canonical) +
                 "', outside the model tree (the directories of --map, --root, the app's "
                 "iri-map, the inputs and mospec's metamodels: " +
                 sandbox_roots() +
                 "); models may only load files inside it (pass --map IRI=DIR to add a "
                 "directory you trust)");
    }
    if (mapped != nullptr) *mapped = std::move(path);
    return canonical;
  }
  if (mapped != nullptr) *mapped = path;
  return path;
}

std::string MappedDocumentLoader::resolve(std::string_view iri) const {
  std::lock_guard lock(sync_->mutex);
  return resolve_locked(iri);
}

std::string MappedDocumentLoader::resolve_locked(std::string_view iri) const {
  // Longest prefix wins, so a mapping for a sub-tree overrides its parent's;
  // fallbacks only where no regular mapping applies.
  const std::pair<const std::string, std::string>* best = nullptr;
  for (const auto* table : {&prefixes_, &fallbacks_}) {
    for (const auto& entry : *table) {
      if (iri.substr(0, entry.first.size()) == entry.first &&
          (best == nullptr || entry.first.size() > best->first.size())) {
        best = &entry;
      }
    }
    if (best != nullptr) break;
  }
  if (best != nullptr) {
    std::string rest = percent_decode(strip_query_fragment(iri.substr(best->first.size())));
    while (!rest.empty() && rest.front() == '/') rest.erase(rest.begin());
    if (best->second.empty()) return rest;
    if (best->second == "/") return "/" + rest;
    return rest.empty() ? best->second : best->second + "/" + rest;
  }
  if (iri.starts_with("file://")) {
    std::string_view rest = strip_query_fragment(iri.substr(7));
    // file://host/path: only the local host is meaningful offline.
    if (rest.starts_with("localhost/")) rest.remove_prefix(9);
    if (!rest.starts_with("/")) return {};
    return percent_decode(rest);
  }
  if (!has_scheme(iri)) return std::string(iri);
  return {};
}

RemoteDocument MappedDocumentLoader::load(std::string_view iri, SourceLoc referenced_from,
                                          bool for_context) {
  std::string_view code = for_context ? kContextFailed : kDocumentFailed;
  std::string_view what = for_context ? "remote context" : "document";
  const std::string& ref_file = files_.path(referenced_from.file);
  // Confined, the file read is the checked canonical path (no link swapped in
  // between check and read changes which file that is); messages keep the
  // mapped path the user recognises.
  std::string path;
  std::string read_path;
  bool confined = false;
  {
    std::lock_guard lock(sync_->mutex);
    read_path = resolve_for_loading_locked(iri, referenced_from, code, what, &path);
    confined = confined_;
  }
  try {
    return load_path(path, read_path, std::string(iri), confined);
  } catch (const Error& e) {
    if (e.code() != kDocumentFailed) throw;  // JSON syntax errors keep their own location
    // Re-issue at the reference, with the code the caller asked for.
    throw Error(std::string(code),
                "cannot load " + std::string(what) + " <" + escaped_bytes(iri) +
                    ">: " + e.diagnostic().message,
                ref_file, referenced_from.line, referenced_from.column);
  }
}

RemoteDocument MappedDocumentLoader::load_file(const std::string& path, std::string document_url) {
  return load_path(path, path, std::move(document_url));
}

RemoteDocument MappedDocumentLoader::load_path(const std::string& path,
                                               const std::string& read_path,
                                               std::string document_url,
                                               bool read_path_is_canonical) {
  std::string key;
  {
    std::lock_guard lock(sync_->mutex);
    key = read_path_is_canonical ? read_path : canonical_.canonical(read_path);
    if (auto it = cache_.find(key); it != cache_.end()) {
      RemoteDocument result = it->second;
      if (!document_url.empty()) result.document_url = std::move(document_url);
      return result;
    }
  }
  // Read and parsed outside the lock, so other threads parse beside this one,
  // each in a buffer of the pool (given back however this ends).
  struct BufferLease {
    Sync& sync;
    Sync::Buffers buffers;
    std::string& text = buffers.text;
    explicit BufferLease(Sync& s) : sync(s) {
      {
        std::lock_guard lock(sync.mutex);
        if (!sync.read_buffers.empty()) {
          buffers = std::move(sync.read_buffers.back());
          sync.read_buffers.pop_back();
        }
      }
      if (!buffers.scratch) buffers.scratch = std::make_unique<json::ParseScratch>();
    }
    ~BufferLease() {
      std::lock_guard lock(sync.mutex);
      try {
        sync.read_buffers.push_back(std::move(buffers));
      } catch (const std::bad_alloc&) {  // the buffers are dropped instead
      }
    }
    BufferLease(const BufferLease&) = delete;
    BufferLease& operator=(const BufferLease&) = delete;
  };
  BufferLease buffer(*sync_);
  const std::string& text = buffer.text;
  // Regular files of bounded size only: a device or a FIFO would block or
  // never end, and a huge file would exhaust memory.
  if (std::string reason = read_file_reason(read_path, buffer.text); !reason.empty()) {
    throw Error(std::string(kDocumentFailed), "cannot read '" + path + "': " + reason, path);
  }
  RemoteDocument doc;
  doc.file_id = files_.add(path);
  doc.content_type = "application/ld+json";
  // The document's values live in an arena that lives as long as they do:
  // parsing costs a pointer bump per string, array and object, and the
  // document is freed in a few blocks when its last user lets go.
  auto parsed = std::make_shared<ParsedDocument>(text.size());
  json::Value* root =
      static_cast<json::Value*>(parsed->arena.allocate(sizeof(json::Value), alignof(json::Value)));
  parsed->root = new (root) json::Value(
      json::parse(text, doc.file_id, path, &parsed->arena, buffer.buffers.scratch.get()));
  assert(json::lives_in(*parsed->root, &parsed->arena));
  doc.document = std::shared_ptr<const json::Value>(parsed, parsed->root);
  doc.document_url = file_url(key);
  RemoteDocument result;
  {
    std::lock_guard lock(sync_->mutex);
    auto [it, fresh] = cache_.emplace(key, std::move(doc));
    if (fresh) ++reads_;
    result = it->second;
  }
  if (!document_url.empty()) result.document_url = std::move(document_url);
  return result;
}

}  // namespace mospec::jsonld
