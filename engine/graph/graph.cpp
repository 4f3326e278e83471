#include "graph/graph.h"

#include "gpu/formats.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <queue>
#include <set>

namespace tl::graph {

// ---- descriptions ------------------------------------------------------------------------

ResourceDesc ResourceDesc::image2D(VkFormat f, uint32_t w, uint32_t h, std::string what, uint32_t mips) {
  return {ResourceType::Image, f, {w, h, 1}, mips, 0, std::move(what)};
}

ResourceDesc ResourceDesc::image3D(VkFormat f, uint32_t w, uint32_t h, uint32_t d, std::string what, uint32_t mips) {
  return {ResourceType::Image, f, {w, h, d}, mips, 0, std::move(what)};
}

ResourceDesc ResourceDesc::buffer(VkDeviceSize bytes, std::string what) {
  return {ResourceType::Buffer, VK_FORMAT_UNDEFINED, {1, 1, 1}, 1, bytes, std::move(what)};
}

std::string formatName(VkFormat format) {
  auto fi = gpu::formatInfo(format);
  return fi.bytes ? fi.name : fmt::format("VkFormat({})", int(format));
}

uint32_t formatBytesPerTexel(VkFormat format) { return gpu::formatInfo(format).bytes; }

VkDeviceSize approximateBytes(const ResourceDesc& d) {
  if (d.type == ResourceType::Buffer) return d.size;
  VkDeviceSize total = 0;
  uint32_t w = d.extent.width, h = d.extent.height, z = d.extent.depth;
  for (uint32_t m = 0; m < std::max(1u, d.mipLevels); ++m) {
    total += VkDeviceSize(w) * h * z * formatBytesPerTexel(d.format);
    w = std::max(1u, w / 2), h = std::max(1u, h / 2), z = std::max(1u, z / 2);
  }
  return total;
}

// ---- declaration -------------------------------------------------------------------------

void PassBuilder::create(std::string_view name, const ResourceDesc& desc, Usage usage) {
  ResourceDecl r;
  r.name = std::string(name);
  r.desc = desc;
  r.creator = pass_;
  graph_.resources_.push_back(std::move(r));
  write(name, usage);
}

void PassBuilder::read(std::string_view name, Usage usage, std::optional<PassKind> as) {
  auto& p = graph_.passes_[pass_];
  p.readNames.emplace_back(name);
  p.readUsages.push_back(usage);
  p.readKinds.push_back(as.value_or(p.kind));
}

void PassBuilder::write(std::string_view name, Usage usage, std::optional<PassKind> as) {
  auto& p = graph_.passes_[pass_];
  p.writeNames.emplace_back(name);
  p.writeUsages.push_back(usage);
  p.writeKinds.push_back(as.value_or(p.kind));
  p.writeUpdates.push_back(false);
}

void PassBuilder::update(std::string_view name, Usage usage, std::optional<PassKind> as) {
  write(name, usage, as);
  graph_.passes_[pass_].writeUpdates.back() = true;
}

void PassBuilder::sideEffect() { graph_.passes_[pass_].sideEffect = true; }

void RenderGraph::declarePersistent(std::string_view name, const ResourceDesc& desc) {
  ResourceDecl r;
  r.name = std::string(name);
  r.desc = desc;
  r.persistent = true;
  resources_.push_back(std::move(r));
}

void RenderGraph::declareOnDemandHistory(std::string_view name, const ResourceDesc& desc) {
  declarePersistent(name, desc);
  resources_.back().onDemand = true;
}

void RenderGraph::declareCache(std::string_view name, const ResourceDesc& desc) {
  declarePersistent(name, desc);
  resources_.back().cache = true;
}

void RenderGraph::declareImported(std::string_view name, const ResourceDesc& desc) {
  ResourceDecl r;
  r.name = std::string(name);
  r.desc = desc;
  r.imported = true;
  resources_.push_back(std::move(r));
}

void RenderGraph::importBuffer(std::string_view name, const ResourceDesc& desc, gpu::Buffer& buffer) {
  declareImported(name, desc);
  resources_.back().importedBuffer = &buffer;
}

PassId RenderGraph::addPass(std::string_view name, PassKind kind, const std::function<void(PassBuilder&)>& setup,
                            ExecuteFn execute) {
  PassId id = PassId(passes_.size());
  PassDecl p;
  p.name = std::string(name);
  p.kind = kind;
  p.execute = std::move(execute);
  passes_.push_back(std::move(p));
  PassBuilder b(*this, id);
  if (setup) setup(b);
  return id;
}

void RenderGraph::markOutput(std::string_view name) {
  if (std::find(outputs_.begin(), outputs_.end(), name) == outputs_.end()) outputs_.emplace_back(name);
}

std::optional<ResourceId> RenderGraph::find(std::string_view name) const {
  for (ResourceId i = 0; i < resources_.size(); ++i)
    if (resources_[i].name == name) return i;
  return std::nullopt;
}

// ---- compile -----------------------------------------------------------------------------

namespace {

size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
      diag = up;
    }
  }
  return row[b.size()];
}

bool attachment(Usage u) {
  return u == Usage::ColorAttachment || u == Usage::DepthAttachment || u == Usage::DepthRead;
}

// One pass using an image two ways at once needs one layout for both: the read-only layout
// when both only read, else GENERAL (valid for every access).
VkImageLayout mergedLayout(VkImageLayout a, VkImageLayout b) {
  if (a == b) return a;
  auto readOnly = [](VkImageLayout l) {
    return l == VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL || l == VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL;
  };
  return readOnly(a) && readOnly(b) ? VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_GENERAL;
}

std::string passList(const std::vector<PassDecl>& passes, const std::vector<PassId>& ids) {
  std::string out;
  for (PassId id : ids) out += (out.empty() ? "`" : ", `") + passes[id].name + "`";
  return out;
}

}  // namespace

CompiledGraph RenderGraph::compile(const EntryStates& entry) const {
  const size_t nPasses = passes_.size(), nRes = resources_.size();

  // 1. Names: unique resources, every access resolved, one writer per resource (or the
  //    steps of one write, PassBuilder::update).
  std::map<std::string, ResourceId, std::less<>> byName;
  for (ResourceId i = 0; i < nRes; ++i) {
    auto [it, fresh] = byName.emplace(resources_[i].name, i);
    if (!fresh) {
      const auto& first = resources_[it->second];
      auto who = [&](const ResourceDecl& r) {
        return r.creator != kNone ? fmt::format("pass `{}`", passes_[r.creator].name)
                                  : std::string(r.persistent ? "a persistent declaration" : "an import");
      };
      throw GraphError(fmt::format("resource `{}` is declared twice: by {} and by {}", resources_[i].name, who(first),
                                   who(resources_[i])));
    }
  }
  auto resolve = [&](const std::string& name, const PassDecl& pass, const char* verb) -> ResourceId {
    auto it = byName.find(name);
    if (it != byName.end()) return it->second;
    std::string suggestion;
    size_t best = std::max<size_t>(3, name.size() / 3) + 1;
    for (auto& [candidate, id] : byName) {
      size_t d = editDistance(name, candidate);
      if (d < best) best = d, suggestion = candidate;
    }
    throw GraphError(fmt::format("pass `{}` {} `{}`, which no pass writes and is not declared{}", pass.name, verb, name,
                                 suggestion.empty() ? "" : fmt::format(" (did you mean `{}`?)", suggestion)));
  };

  CompiledGraph out;
  out.resources.resize(nRes);
  for (ResourceId i = 0; i < nRes; ++i) out.resources[i].id = i;
  std::vector<std::vector<Access>> reads(nPasses), writes(nPasses);
  for (PassId p = 0; p < nPasses; ++p) {
    const auto& pass = passes_[p];
    for (size_t i = 0; i < pass.readNames.size(); ++i)
      reads[p].push_back({resolve(pass.readNames[i], pass, "reads"), pass.readUsages[i], pass.readKinds[i]});
    for (size_t i = 0; i < pass.writeNames.size(); ++i) {
      ResourceId r = resolve(pass.writeNames[i], pass, "writes");
      writes[p].push_back({r, pass.writeUsages[i], pass.writeKinds[i]});
      auto& info = out.resources[r];
      if (info.writer == p) continue;
      if (pass.writeUpdates[i] && info.writer == kNone)
        throw GraphError(fmt::format("pass `{}` updates `{}`, which no pass declared before it writes", pass.name,
                                     resources_[r].name));
      if (!pass.writeUpdates[i] && info.writer != kNone)
        throw GraphError(fmt::format("resource `{}` is written by both `{}` and `{}`", resources_[r].name,
                                     passes_[info.writer].name, pass.name));
      info.writer = p;
      info.steps.push_back(p);
    }
  }
  for (PassId p = 0; p < nPasses; ++p) {
    for (auto& a : reads[p]) {
      const auto& r = resources_[a.resource];
      auto& info = out.resources[a.resource];
      if (info.writer == kNone && !r.persistent && !r.imported)
        throw GraphError(fmt::format("pass `{}` reads `{}`, which no pass writes", passes_[p].name, r.name));
      if (std::find(info.readers.begin(), info.readers.end(), p) == info.readers.end()) info.readers.push_back(p);
    }
  }
  for (auto& name : outputs_)
    if (!byName.count(name)) throw GraphError(fmt::format("frame output `{}` is not a resource of the graph", name));

  // Each pass's usages of one resource merged into one access; a usage its kind of pass
  // cannot make, or one that does not fit the resource's type, is misuse.
  std::vector<std::vector<PassAccess>> passAccesses(nPasses);
  for (PassId p = 0; p < nPasses; ++p) {
    const auto& pass = passes_[p];
    std::map<ResourceId, PassAccess> merged;
    auto add = [&](const Access& a) {
      const auto& r = resources_[a.resource];
      StageAccess scope;
      VkImageLayout layout;
      if (!accessFor(a.usage, a.kind, scope, layout))
        throw GraphError(fmt::format("pass `{}` ({}) cannot use `{}` as {}", pass.name, kindName(a.kind), r.name,
                                     usageName(a.usage)));
      const bool image = r.desc.type == ResourceType::Image;
      if (image ? layout == VK_IMAGE_LAYOUT_UNDEFINED : attachment(a.usage))
        throw GraphError(fmt::format("pass `{}` uses `{}` as {}, which needs {}", pass.name, r.name, usageName(a.usage),
                                     image ? "a buffer" : "an image"));
      auto [it, fresh] = merged.try_emplace(a.resource);
      PassAccess& m = it->second;
      m.resource = a.resource;
      m.scope.stages |= scope.stages;
      m.scope.access |= scope.access;
      m.writes |= isWrite(a.usage);
      m.layout = fresh ? layout : mergedLayout(m.layout, layout);
    };
    for (auto& a : reads[p]) add(a);
    for (auto& a : writes[p]) add(a);
    for (auto& [r, a] : merged) passAccesses[p].push_back(a);
  }

  // 2. Dependencies. Transient, imported and caches: writer before readers. Persistent: a
  //    reader other than the writer sees last frame's contents, so it must run before the writer.
  std::vector<std::set<PassId>> after(nPasses);  // edges p -> q: q runs after p
  std::vector<size_t> indegree(nPasses, 0);
  auto edge = [&](PassId from, PassId to) {
    if (from != to && after[from].insert(to).second) ++indegree[to];
  };
  //    Steps of one write (PassBuilder::update) run in declaration order; readers that are
  //    not steps see the last (a history's, last frame's contents: before the first).
  for (ResourceId r = 0; r < nRes; ++r) {
    const auto& info = out.resources[r];
    if (info.writer == kNone) continue;
    for (size_t i = 1; i < info.steps.size(); ++i) edge(info.steps[i - 1], info.steps[i]);
    for (PassId reader : info.readers) {
      if (std::find(info.steps.begin(), info.steps.end(), reader) != info.steps.end()) continue;
      if (resources_[r].persistent && !resources_[r].cache) edge(reader, info.steps.front());
      else edge(info.writer, reader);
    }
  }
  // Kahn's algorithm, declaration order breaking ties.
  std::priority_queue<PassId, std::vector<PassId>, std::greater<>> ready;
  for (PassId p = 0; p < nPasses; ++p)
    if (indegree[p] == 0) ready.push(p);
  std::vector<PassId> sorted;
  while (!ready.empty()) {
    PassId p = ready.top();
    ready.pop();
    sorted.push_back(p);
    for (PassId q : after[p])
      if (--indegree[q] == 0) ready.push(q);
  }
  if (sorted.size() != nPasses) {
    std::vector<PassId> stuck;
    for (PassId p = 0; p < nPasses; ++p)
      if (indegree[p] > 0) stuck.push_back(p);
    throw GraphError(fmt::format("the passes {} depend on each other in a cycle", passList(passes_, stuck)));
  }

  // 3. Culling: keep what the frame exists for, then everything those passes read from.
  std::vector<bool> keep(nPasses, false);
  std::vector<PassId> work;
  auto keepPass = [&](PassId p) {
    if (!keep[p]) keep[p] = true, work.push_back(p);
  };
  for (PassId p = 0; p < nPasses; ++p) {
    bool root = passes_[p].sideEffect;
    for (auto& w : writes[p]) {
      const auto& r = resources_[w.resource];
      root |= (r.persistent && !r.onDemand) || r.imported ||
              std::find(outputs_.begin(), outputs_.end(), r.name) != outputs_.end();
    }
    if (root) keepPass(p);
  }
  while (!work.empty()) {
    PassId p = work.back();
    work.pop_back();
    for (auto& a : reads[p])
      if (PassId w = out.resources[a.resource].writer; w != kNone) keepPass(w);
    for (auto& a : writes[p])  // the steps of one write stand or fall together
      for (PassId step : out.resources[a.resource].steps) keepPass(step);
  }

  // 4. Order, barriers and lifetimes of the surviving passes: each resource's state walks
  //    through the frame from the state it entered in (barriers.h has the rules).
  out.entry.resize(nRes);
  for (ResourceId r = 0; r < nRes; ++r) {
    const auto& decl = resources_[r];
    if (!decl.persistent && !decl.imported) continue;
    if (auto it = entry.find(decl.name); it != entry.end()) out.entry[r] = carriedOver(it->second);
  }
  out.exit = out.entry;
  for (PassId p : sorted) {
    if (!keep[p]) {
      out.culled.push_back(p);
      continue;
    }
    const uint32_t index = uint32_t(out.order.size());
    CompiledPass cp;
    cp.pass = p;
    cp.reads = reads[p];
    cp.writes = writes[p];
    cp.accesses = passAccesses[p];
    for (const PassAccess& a : cp.accesses) {
      auto& info = out.resources[a.resource];
      if (info.firstUse == kNone) info.firstUse = index;
      info.lastUse = index;
      const bool image = resources_[a.resource].desc.type == ResourceType::Image;
      if (auto b = advance(out.exit[a.resource], a.resource, a, image, p)) cp.barriers.push_back(std::move(*b));
    }
    out.order.push_back(std::move(cp));
  }
  for (auto& info : out.resources) info.culled = info.firstUse == kNone;
  return out;
}

// ---- aliasing ----------------------------------------------------------------------------

AliasPlan planAliasing(const std::vector<AliasRequest>& requests) {
  AliasPlan plan;
  plan.offsets.assign(requests.size(), 0);
  std::vector<size_t> order(requests.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return requests[a].size > requests[b].size; });

  std::vector<size_t> placed;
  for (size_t i : order) {
    const auto& r = requests[i];
    plan.unaliasedSize += r.size;
    if (r.size == 0) continue;
    // Byte ranges already taken by requests alive at the same time, by start.
    std::vector<std::pair<VkDeviceSize, VkDeviceSize>> busy;
    for (size_t j : placed) {
      const auto& o = requests[j];
      if (o.firstPass <= r.lastPass && r.firstPass <= o.lastPass) busy.push_back({plan.offsets[j], plan.offsets[j] + o.size});
    }
    std::sort(busy.begin(), busy.end());
    const VkDeviceSize align = std::max<VkDeviceSize>(1, r.alignment);
    VkDeviceSize offset = 0;
    for (auto& [start, end] : busy) {
      if (offset + r.size <= start) break;  // fits in the gap before this range
      offset = std::max(offset, (end + align - 1) / align * align);
    }
    plan.offsets[i] = offset;
    plan.totalSize = std::max(plan.totalSize, offset + r.size);
    placed.push_back(i);
  }
  return plan;
}

// ---- dump --------------------------------------------------------------------------------

namespace {

std::string describe(const ResourceDesc& d) {
  if (d.type == ResourceType::Buffer) return fmt::format("buffer {} B", d.size);
  std::string size = d.extent.depth > 1 ? fmt::format("{}x{}x{}", d.extent.width, d.extent.height, d.extent.depth)
                                        : fmt::format("{}x{}", d.extent.width, d.extent.height);
  return fmt::format("{} {}{}", formatName(d.format), size, d.mipLevels > 1 ? fmt::format(" {} mips", d.mipLevels) : "");
}

std::string mib(VkDeviceSize bytes) { return fmt::format("{:.2f} MiB", double(bytes) / (1024.0 * 1024.0)); }

}  // namespace

std::string RenderGraph::describeBarrier(const Barrier& b) const {
  auto side = [](const StageAccess& sa) {
    return sa.access ? fmt::format("{} [{}]", stageNames(sa.stages), accessNames(sa.access)) : stageNames(sa.stages);
  };
  std::string s = fmt::format("{}: {} -> {}", resources_[b.resource].name, side(b.src), side(b.dst));
  if (resources_[b.resource].desc.type == ResourceType::Image) {
    s += fmt::format(", {} -> {}", layoutName(b.oldLayout), layoutName(b.newLayout));
    if (b.transition() && b.oldLayout == VK_IMAGE_LAYOUT_UNDEFINED) s += " (discard)";
  }
  for (size_t i = 0; i < b.waitsFor.size(); ++i) {
    s += i == 0 ? "; after " : ", ";
    s += b.waitsFor[i] == kNone ? fmt::format("the previous frame") : fmt::format("`{}`", passes_[b.waitsFor[i]].name);
  }
  return s;
}

std::string RenderGraph::dump(const CompiledGraph& c) const {
  // Transient memory with and without aliasing, from the description sizes.
  std::vector<AliasRequest> requests;
  for (auto& info : c.resources) {
    const auto& r = resources_[info.id];
    if (info.culled || r.persistent || r.imported || r.desc.type != ResourceType::Image) continue;
    requests.push_back({approximateBytes(r.desc), 256, info.firstUse, info.lastUse});
  }
  AliasPlan plan = planAliasing(requests);

  std::string s = fmt::format("render graph: {} passes ({} culled), {} resources, transient images {} aliased into {}\n",
                              c.order.size() + c.culled.size(), c.culled.size(), resources_.size(),
                              mib(plan.unaliasedSize), mib(plan.totalSize));
  for (size_t i = 0; i < c.order.size(); ++i) {
    const auto& cp = c.order[i];
    s += fmt::format("[{}] {} ({})\n", i, passes_[cp.pass].name, kindName(passes_[cp.pass].kind));
    const PassKind kind = passes_[cp.pass].kind;
    auto usage = [&](const Access& a) {
      return a.kind == kind ? std::string(usageName(a.usage)) : fmt::format("{}, {}", usageName(a.usage), kindName(a.kind));
    };
    for (auto& a : cp.reads)
      s += fmt::format("      reads  {:22} {:24} ({})\n", resources_[a.resource].name, describe(resources_[a.resource].desc),
                       usage(a));
    for (auto& a : cp.writes)
      s += fmt::format("      writes {:22} {:24} ({})\n", resources_[a.resource].name, describe(resources_[a.resource].desc),
                       usage(a));
    for (auto& b : cp.barriers) s += "      barrier " + describeBarrier(b) + "\n";
  }
  s += "resources:\n";
  for (auto& info : c.resources) {
    const auto& r = resources_[info.id];
    std::string writer = info.writer != kNone ? passes_[info.writer].name : (r.imported ? "(imported)" : "(none)");
    std::string earlier;  // the steps before the last (PassBuilder::update)
    for (size_t i = 0; i + 1 < info.steps.size(); ++i) earlier += (earlier.empty() ? "" : ", ") + passes_[info.steps[i]].name;
    if (!earlier.empty()) writer += " (after " + earlier + ")";
    std::string readers;
    for (PassId p : info.readers)
      if (std::find(c.culled.begin(), c.culled.end(), p) == c.culled.end())
        readers += (readers.empty() ? "" : ",") + passes_[p].name;
    std::string life = info.culled ? "culled" : fmt::format("life [{}..{}]", info.firstUse, info.lastUse);
    s += fmt::format("  {:22} {:26} {:>10}  written by {}  read by {}  {}{}{}\n", r.name, describe(r.desc),
                     mib(approximateBytes(r.desc)), writer, readers.empty() ? "-" : readers, life,
                     r.persistent ? "  persistent" : "", r.desc.description.empty() ? "" : "  -- " + r.desc.description);
  }
  if (!c.culled.empty()) {
    s += "culled:\n";
    for (PassId p : c.culled) {
      std::string outs;
      for (auto& n : passes_[p].writeNames) outs += (outs.empty() ? "" : ", ") + n;
      s += fmt::format("  {} (nobody reads {})\n", passes_[p].name, outs.empty() ? "anything it writes" : outs);
    }
  }
  return s;
}

namespace {

// A DOT string literal: quotes and backslashes escaped, line breaks as DOT's \n.
std::string dotQuote(std::string_view text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

}  // namespace

std::string RenderGraph::dot(const CompiledGraph& c) const {
  // Passes are boxes in execution order, resources ellipses between their writer and their
  // readers; persistent resources have a double border, imported ones a dashed one; culled
  // passes and the resources only they touch are grey.
  std::string s = "digraph twinlight {\n  rankdir=LR;\n  node [fontname=\"Helvetica\", fontsize=10];\n"
                  "  edge [color=\"#555555\"];\n";
  auto passNode = [](std::string_view name) { return dotQuote("pass:" + std::string(name)); };
  auto resourceNode = [](std::string_view name) { return dotQuote("resource:" + std::string(name)); };
  for (size_t i = 0; i < c.order.size(); ++i) {
    const PassDecl& p = passes_[c.order[i].pass];
    s += fmt::format("  {} [shape=box, style=filled, fillcolor=\"#dde6f7\", label={}];\n", passNode(p.name),
                     dotQuote(fmt::format("[{}] {}\n{}", i, p.name, kindName(p.kind))));
  }
  for (PassId p : c.culled)
    s += fmt::format("  {} [shape=box, style=dashed, color=grey, fontcolor=grey, label={}];\n", passNode(passes_[p].name),
                     dotQuote(passes_[p].name + "\nculled"));
  for (const ResourceInfo& info : c.resources) {
    const ResourceDecl& r = resources_[info.id];
    std::string style = r.imported ? "dashed" : "solid";
    s += fmt::format("  {} [shape=ellipse, style={}{}{}, label={}];\n", resourceNode(r.name), style,
                     r.persistent ? ", peripheries=2" : "", info.culled ? ", color=grey, fontcolor=grey" : "",
                     dotQuote(r.name + "\n" + describe(r.desc)));
  }
  auto edges = [&](PassId pass, bool culled) {
    const PassDecl& p = passes_[pass];
    const char* grey = culled ? " [color=grey]" : "";
    for (const auto& name : p.readNames) s += fmt::format("  {} -> {}{};\n", resourceNode(name), passNode(p.name), grey);
    for (size_t w = 0; w < p.writeNames.size(); ++w)
      s += fmt::format("  {} -> {} [label={}{}];\n", passNode(p.name), resourceNode(p.writeNames[w]),
                       dotQuote(usageName(p.writeUsages[w])), culled ? ", color=grey" : "");
  };
  for (const CompiledPass& cp : c.order) edges(cp.pass, false);
  for (PassId p : c.culled) edges(p, true);
  return s + "}\n";
}

}  // namespace tl::graph
