#include "patch_quads.hpp"

#include "laytracks/mesher/mesh_part.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <thread>

namespace laytracks::mesher_detail {

namespace {
constexpr std::uint32_t kUnset = 0xffffffffu;
}  // namespace

std::vector<bool> vertex_nodes(const Part& part, const QuadMesh& mesh) {
  const double tol = MeshTolerances::kOnBrep * part.size;  // at a vertex, as the check says
  std::vector<bool> vertex(mesh.nodes.size(), false);
  // Nodes by sorted x.
  std::vector<std::pair<double, std::uint32_t>> by_x;
  for (std::uint32_t v = 0; v < mesh.nodes.size(); ++v) by_x.emplace_back(mesh.nodes[v].x, v);
  std::sort(by_x.begin(), by_x.end());
  for (const auto& pv : part.vertices) {
    auto it = std::lower_bound(by_x.begin(), by_x.end(), std::make_pair(pv.position.x - tol, 0u));
    for (; it != by_x.end() && it->first <= pv.position.x + tol; ++it)
      if (distance(mesh.nodes[it->second], pv.position) <= tol) vertex[it->second] = true;
  }
  return vertex;
}

std::vector<std::vector<std::uint32_t>> quads_at_mesh_nodes(const QuadMesh& mesh) {
  std::vector<std::vector<std::uint32_t>> around(mesh.nodes.size());
  for (std::uint32_t q = 0; q < mesh.elements.size(); ++q)
    if (mesh.elements[q].is_quad())
      for (std::uint32_t v : mesh.elements[q].nodes) around[v].push_back(q);
  return around;
}

std::vector<bool> shared_nodes(const QuadMesh& mesh) {
  std::vector<std::uint32_t> patch_of(mesh.nodes.size(), kUnset);
  std::vector<bool> shared(mesh.nodes.size(), false);
  for (const MeshElement& e : mesh.elements) {
    const std::size_t corners = e.is_quad() ? 4 : 3;
    for (std::size_t k = 0; k < corners; ++k) {
      const std::uint32_t v = e.nodes[k];
      if (patch_of[v] == kUnset)
        patch_of[v] = e.patch.value;
      else if (patch_of[v] != e.patch.value)
        shared[v] = true;
    }
  }
  return shared;
}

EdgesByNode edges_by_lower_node(const QuadMesh& mesh,
                                const std::function<bool(std::size_t)>& counted) {
  const std::size_t n = mesh.nodes.size();
  EdgesByNode out;
  out.start.assign(n + 1, 0);
  const auto for_edges = [&](auto&& fn) {
    for (std::size_t ei = 0; ei < mesh.elements.size(); ++ei) {
      if (!counted(ei)) continue;
      const MeshElement& e = mesh.elements[ei];
      const std::size_t corners = e.is_quad() ? 4 : 3;
      for (std::size_t k = 0; k < corners; ++k) {
        const auto [a, b] = std::minmax(e.nodes[k], e.nodes[(k + 1) % corners]);
        fn(a, b, static_cast<std::uint32_t>(ei));
      }
    }
  };
  for_edges([&](std::uint32_t a, std::uint32_t, std::uint32_t) { ++out.start[a + 1]; });
  for (std::size_t v = 0; v < n; ++v) out.start[v + 1] += out.start[v];
  out.uses.resize(out.start.back());
  std::vector<std::uint32_t> fill(out.start.begin(), out.start.end() - 1);
  for_edges([&](std::uint32_t a, std::uint32_t b, std::uint32_t ei) { out.uses[fill[a]++] = {b, ei}; });
  for (std::size_t a = 0; a < n; ++a)
    std::sort(out.uses.begin() + out.start[a], out.uses.begin() + out.start[a + 1]);
  return out;
}

std::vector<bool> pinned_nodes(const QuadMesh& mesh) {
  std::vector<bool> pinned = shared_nodes(mesh);
  // An edge that one element uses is on a boundary.
  const EdgesByNode edges = edges_by_lower_node(mesh, [](std::size_t) { return true; });
  for (std::size_t a = 0; a + 1 < edges.start.size(); ++a) {
    const auto first = edges.uses.begin() + edges.start[a], last = edges.uses.begin() + edges.start[a + 1];
    for (auto i = first; i != last;) {
      auto j = i + 1;
      while (j != last && j->first == i->first) ++j;
      if (j - i == 1) {
        pinned[a] = true;
        pinned[i->first] = true;
      }
      i = j;
    }
  }
  return pinned;
}

std::vector<std::vector<std::uint32_t>> elements_by_patch(const Part& part, const QuadMesh& mesh) {
  std::vector<std::vector<std::uint32_t>> by(part.patches.size());
  for (std::size_t i = 0; i < mesh.elements.size(); ++i)
    by[mesh.elements[i].patch.index()].push_back(static_cast<std::uint32_t>(i));
  return by;
}

std::vector<std::size_t> busy_patches(const std::vector<std::vector<std::uint32_t>>& by_patch) {
  std::vector<std::size_t> busy;
  for (std::size_t p = 0; p < by_patch.size(); ++p)
    if (!by_patch[p].empty()) busy.push_back(p);
  return busy;
}

PatchQuads patch_quads(const Part& part,
                       const QuadMesh& mesh,
                       std::size_t p,
                       const std::vector<std::uint32_t>& elements,
                       const std::vector<bool>& pinned) {
  const Frame& frame = part.patches[p].frame;
  PatchQuads pq;
  std::vector<std::uint32_t> local(mesh.nodes.size(), kUnset);
  for (const std::uint32_t i : elements) {
    const MeshElement& e = mesh.elements[i];
    if (!e.is_quad()) continue;
    std::array<std::uint32_t, 4> q{};
    for (std::size_t k = 0; k < 4; ++k) {
      const std::uint32_t v = e.nodes[k];
      if (local[v] == kUnset) {
        local[v] = static_cast<std::uint32_t>(pq.global.size());
        pq.global.push_back(v);
        pq.pos.push_back(frame.to_2d(mesh.nodes[v]));
        pq.fixed.push_back(pinned[v]);
      }
      q[k] = local[v];
    }
    pq.quads.push_back(q);
    pq.elements.push_back(i);
  }
  return pq;
}

namespace {
std::atomic<std::size_t> g_mesher_threads{0};
}  // namespace

std::size_t worker_threads() {
  static const std::size_t from_env = [] {
    const char* env = std::getenv("LAYTRACKS_THREADS");
    if (env != nullptr) {
      char* end = nullptr;
      const long n = std::strtol(env, &end, 10);
      if (end != env && *end == '\0' && n >= 1) return static_cast<std::size_t>(n);
    }
    return std::size_t{0};
  }();
  if (from_env != 0) return from_env;
  const std::size_t set = g_mesher_threads.load();
  if (set != 0) return set;
  return static_cast<std::size_t>(std::max(1u, std::thread::hardware_concurrency()));
}

namespace {
/// Set while a thread works for a parallel_for: one called from there runs on that thread.
thread_local bool t_in_parallel_for = false;

/// Threads kept waiting for parallel_for's work: a sweep pass of a large patch is a few
/// parallel_for calls of a millisecond or less each (SweepSchedule), and starting threads for
/// each cost as much as the work saved. One caller at a time (a batch's parts mesh at once,
/// each on its own thread): run() says no to the others, which start threads of their own.
class WorkerPool {
 public:
  ~WorkerPool() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
  }

  /// Runs `work` on `helpers` threads of the pool and on the calling thread; returns once all
  /// have returned. False, having run nothing, when another caller is using the pool.
  bool run(std::size_t helpers, const std::function<void()>& work) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (busy_) return false;
    busy_ = true;
    while (threads_.size() < helpers) threads_.emplace_back([this] { serve(); });
    work_ = &work;
    open_ = helpers;
    running_ = helpers;
    lock.unlock();
    wake_.notify_all();
    work();
    lock.lock();
    done_.wait(lock, [this] { return running_ == 0; });
    work_ = nullptr;
    busy_ = false;
    return true;
  }

 private:
  void serve() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      wake_.wait(lock, [this] { return stop_ || open_ > 0; });
      if (stop_) return;
      --open_;
      const std::function<void()>* work = work_;
      lock.unlock();
      (*work)();
      lock.lock();
      if (--running_ == 0) done_.notify_one();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_, done_;
  std::vector<std::thread> threads_;
  const std::function<void()>* work_ = nullptr;
  std::size_t open_ = 0;     // places of the present work not yet taken by a thread
  std::size_t running_ = 0;  // places of the present work not yet finished
  bool busy_ = false, stop_ = false;
};

WorkerPool& worker_pool() {
  static WorkerPool pool;
  return pool;
}
}  // namespace

void parallel_for(std::size_t n, const std::function<void(std::size_t)>& fn) {
  const std::size_t threads = t_in_parallel_for ? 1 : std::min(n, worker_threads());
  if (threads <= 1) {
    for (std::size_t i = 0; i < n; ++i) fn(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::atomic<std::size_t> error_index{n};  // written under error_mutex, read without it
  std::mutex error_mutex;
  auto work = [&] {
    const bool outer = t_in_parallel_for;
    t_in_parallel_for = true;
    for (std::size_t i = next++; i < n; i = next++) {
      // After a failure at index e, the items after it need not run: the error thrown is the
      // least index's, as one thread running them in order would meet first.
      if (error_index.load(std::memory_order_relaxed) < i) continue;
      try {
        fn(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (i < error_index) {
          error = std::current_exception();
          error_index.store(i, std::memory_order_relaxed);
        }
      }
    }
    t_in_parallel_for = outer;
  };
  const std::function<void()> job = work;
  if (!worker_pool().run(threads - 1, job)) {
    std::vector<std::thread> pool;
    for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
  }
  if (error) std::rethrow_exception(error);
}

MeshElement element_of(const PatchQuads& pq, const std::array<std::uint32_t, 4>& q,
                       std::size_t p, std::uint32_t shell) {
  MeshElement e;
  for (std::size_t m = 0; m < 4; ++m) e.nodes[m] = pq.global[q[m]];
  e.patch = PatchId(static_cast<std::uint32_t>(p));
  e.shell = shell;
  return e;
}

void replace_elements(QuadMesh& mesh, const std::vector<bool>& drop,
                      const std::vector<MeshElement>& added) {
  constexpr std::uint32_t kUnused = 0xffffffffu;
  std::vector<MeshElement> elements;
  for (std::size_t i = 0; i < mesh.elements.size(); ++i)
    if (!drop[i]) elements.push_back(mesh.elements[i]);
  elements.insert(elements.end(), added.begin(), added.end());
  std::vector<std::uint32_t> renum(mesh.nodes.size(), kUnused);
  for (const MeshElement& e : elements)
    for (std::uint32_t v : e.nodes) renum[v] = 0;
  std::vector<Vec3> nodes;
  for (std::size_t v = 0; v < mesh.nodes.size(); ++v) {
    if (renum[v] == kUnused) continue;
    renum[v] = static_cast<std::uint32_t>(nodes.size());
    nodes.push_back(mesh.nodes[v]);
  }
  for (MeshElement& e : elements)
    for (std::uint32_t& v : e.nodes) v = renum[v];
  mesh.nodes = std::move(nodes);
  mesh.elements = std::move(elements);
}

}  // namespace laytracks::mesher_detail

namespace laytracks {

void set_mesher_threads(std::size_t threads) { mesher_detail::g_mesher_threads = threads; }

}  // namespace laytracks
