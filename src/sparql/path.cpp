// Property-path evaluation over the dataset's posting lists.
//
// Every path is evaluated as "the set of nodes reachable from a set of start
// nodes", in one direction or the other, so a sequence never revisits a node
// twice at the same stage and arbitrary-length paths are a breadth-first
// search with a visited set. Visited sets are stamp arrays indexed by term id
// (reset in O(1) by bumping a generation) taken from the caller's
// PathWorkspace, so a call allocates nothing once the workspace has warmed up.
#include "sparql/path.hpp"

#include <algorithm>
#include <optional>

namespace mospec::sparql {

PathPtr Path::iri(rdf::TermId p) {
  auto path = std::make_shared<Path>();
  path->kind = Kind::Predicate;
  path->predicate = p;
  return path;
}

PathPtr Path::make(Kind k, std::vector<PathPtr> items) {
  auto path = std::make_shared<Path>();
  path->kind = k;
  path->items = std::move(items);
  return path;
}

namespace {

using rdf::TermId;

class MarkSet {
 public:
  void reset(size_t n) {
    if (stamp_.size() < n) stamp_.resize(n, 0);
    if (++gen_ == 0) {
      std::fill(stamp_.begin(), stamp_.end(), 0);
      gen_ = 1;
    }
    outside_.clear();
  }
  // True when newly inserted.
  bool insert(TermId t) {
    if (t.index < stamp_.size()) {
      if (stamp_[t.index] == gen_) return false;
      stamp_[t.index] = gen_;
      return true;
    }
    // Ids outside the dataset (computed terms) are rare: a short list will do.
    if (std::find(outside_.begin(), outside_.end(), t) != outside_.end()) return false;
    outside_.push_back(t);
    return true;
  }

 private:
  std::vector<uint32_t> stamp_;
  uint32_t gen_ = 0;
  std::vector<TermId> outside_;
};

}  // namespace

// Pools used as stacks: nested paths take the next set or list and give it
// back on the way out.
struct PathWorkspace::Buffers {
  std::vector<std::unique_ptr<MarkSet>> marks;
  size_t marks_used = 0;
  std::vector<std::unique_ptr<std::vector<TermId>>> lists;
  size_t lists_used = 0;
};

PathWorkspace::PathWorkspace() : buffers_(std::make_unique<Buffers>()) {}
PathWorkspace::~PathWorkspace() = default;

namespace {

using Workspace = PathWorkspace::Buffers;

class Walker {
 public:
  Walker(const rdf::Dataset& data, TermId graph, Workspace& ws, Budget& budget)
      : data_(data), graph_(graph), ws_(ws), budget_(budget) {}

  // Appends to `out` every node reachable from one of `starts` along `p`
  // (backwards when `inv`) that `seen` does not hold yet.
  void reach(const Path& p, bool inv, std::span<const TermId> starts, std::vector<TermId>& out,
             MarkSet& seen) {
    auto emit = [&](TermId t) {
      budget_.tick();
      if (seen.insert(t)) out.push_back(t);
    };
    switch (p.kind) {
      case Path::Kind::Predicate:
        for (TermId s : starts) {
          if (inv) {
            data_.scan(TermId::any(), p.predicate, s, graph_, [&](const rdf::Quad& q, uint32_t) {
              emit(q.subject);
              return true;
            });
          } else {
            data_.scan(s, p.predicate, TermId::any(), graph_, [&](const rdf::Quad& q, uint32_t) {
              emit(q.object);
              return true;
            });
          }
        }
        return;
      case Path::Kind::Inverse:
        reach(*p.items[0], !inv, starts, out, seen);
        return;
      case Path::Kind::Alternative:
        for (const PathPtr& item : p.items) reach(*item, inv, starts, out, seen);
        return;
      case Path::Kind::Sequence: {
        if (p.items.empty()) {
          for (TermId s : starts) emit(s);
          return;
        }
        ListGuard a(ws_), b(ws_);
        a.list().assign(starts.begin(), starts.end());
        const size_t n = p.items.size();
        for (size_t k = 0; k + 1 < n; ++k) {
          const Path& item = *p.items[inv ? n - 1 - k : k];
          MarkGuard stage(ws_, data_);
          b.list().clear();
          reach(item, inv, a.list(), b.list(), stage.marks());
          std::swap(a.list(), b.list());
          if (a.list().empty()) return;
        }
        reach(*p.items[inv ? 0 : n - 1], inv, a.list(), out, seen);
        return;
      }
      case Path::Kind::ZeroOrOne:
        for (TermId s : starts) emit(s);
        reach(*p.items[0], inv, starts, out, seen);
        return;
      case Path::Kind::ZeroOrMore:
      case Path::Kind::OneOrMore: {
        MarkGuard visited(ws_, data_);
        ListGuard queue(ws_);
        if (p.kind == Path::Kind::ZeroOrMore) {
          for (TermId s : starts)
            if (visited.marks().insert(s)) queue.list().push_back(s);
        } else {
          reach(*p.items[0], inv, starts, queue.list(), visited.marks());
        }
        for (size_t i = 0; i < queue.list().size(); ++i) {
          budget_.tick();
          const TermId node = queue.list()[i];
          emit(node);
          reach(*p.items[0], inv, std::span<const TermId>(&node, 1), queue.list(), visited.marks());
        }
        return;
      }
      case Path::Kind::NegatedSet: {
        auto excluded = [](const std::vector<TermId>& set, TermId pred) {
          return std::find(set.begin(), set.end(), pred) != set.end();
        };
        // !(a|^b) is the union of the forward set over {a} and the inverse set
        // over {b}; each part exists only when it has members.
        const bool forward = !p.negated.empty();
        const bool backward = !p.negated_inverse.empty();
        for (TermId s : starts) {
          // Following the path backwards swaps the two parts.
          if (inv ? forward : backward) {
            const auto& set = inv ? p.negated : p.negated_inverse;
            data_.scan(TermId::any(), TermId::any(), s, graph_, [&](const rdf::Quad& q, uint32_t) {
              if (!excluded(set, q.predicate)) emit(q.subject);
              return true;
            });
          }
          if (inv ? backward : forward) {
            const auto& set = inv ? p.negated_inverse : p.negated;
            data_.scan(s, TermId::any(), TermId::any(), graph_, [&](const rdf::Quad& q, uint32_t) {
              if (!excluded(set, q.predicate)) emit(q.object);
              return true;
            });
          }
        }
        return;
      }
    }
  }

  class MarkGuard {
   public:
    MarkGuard(Workspace& ws, const rdf::Dataset& data) : ws_(ws) {
      if (ws.marks_used == ws.marks.size()) ws.marks.push_back(std::make_unique<MarkSet>());
      marks_ = ws.marks[ws.marks_used++].get();
      marks_->reset(data.terms().size());
    }
    ~MarkGuard() { --ws_.marks_used; }
    MarkGuard(const MarkGuard&) = delete;
    MarkGuard& operator=(const MarkGuard&) = delete;
    MarkSet& marks() { return *marks_; }

   private:
    Workspace& ws_;
    MarkSet* marks_;
  };

  class ListGuard {
   public:
    explicit ListGuard(Workspace& ws) : ws_(ws) {
      if (ws.lists_used == ws.lists.size())
        ws.lists.push_back(std::make_unique<std::vector<TermId>>());
      list_ = ws.lists[ws.lists_used++].get();
      list_->clear();
    }
    ~ListGuard() { --ws_.lists_used; }
    ListGuard(const ListGuard&) = delete;
    ListGuard& operator=(const ListGuard&) = delete;
    std::vector<TermId>& list() { return *list_; }

   private:
    Workspace& ws_;
    std::vector<TermId>* list_;
  };

 private:
  const rdf::Dataset& data_;
  TermId graph_;
  Workspace& ws_;
  Budget& budget_;
};

void run(const rdf::Dataset& data, const Path& path, TermId node, bool inverse,
         std::vector<TermId>& out, TermId graph, Budget* budget, PathWorkspace* workspace) {
  out.clear();
  std::optional<PathWorkspace> own_workspace;
  if (workspace == nullptr) workspace = &own_workspace.emplace();
  Workspace& ws = workspace->buffers();
  std::optional<Budget> own;
  if (budget == nullptr) budget = &own.emplace();
  Walker walker(data, graph, ws, *budget);
  Walker::MarkGuard seen(ws, data);
  walker.reach(path, inverse, std::span<const TermId>(&node, 1), out, seen.marks());
}

}  // namespace

void evaluate_path(const rdf::Dataset& data, const Path& path, rdf::TermId start,
                   std::vector<rdf::TermId>& out, rdf::TermId graph, Budget* budget,
                   PathWorkspace* workspace) {
  run(data, path, start, false, out, graph, budget, workspace);
}

void evaluate_path_inverse(const rdf::Dataset& data, const Path& path, rdf::TermId end,
                           std::vector<rdf::TermId>& out, rdf::TermId graph, Budget* budget,
                           PathWorkspace* workspace) {
  run(data, path, end, true, out, graph, budget, workspace);
}

}  // namespace mospec::sparql
