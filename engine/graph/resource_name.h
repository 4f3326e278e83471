// A frame resource's name with its kind, image or buffer. Passes bind resources through these
// (lighting/common/pass_builders.h), so a buffer bound where an image belongs, or the reverse,
// does not compile; the name itself stays the resource's identity everywhere else (the graph,
// the inspector, captures, the dump), and converts to it (a view or a string).
//
//   inline constexpr graph::ImageName kCompositeHdr{"composite.hdr"};   // a frame's resource
//   pass.sampled(binding, graph::ImageName{historyName});              // a name made at run time
//
// A ResourceName views its characters: what it names must outlive it (constants do; a name
// made at run time is passed on at once, and the builders copy it).
#pragma once

#include <ostream>
#include <string>
#include <string_view>

namespace tl::graph {

template <class Kind>
class ResourceName {
 public:
  constexpr explicit ResourceName(std::string_view name) : name_(name) {}
  constexpr std::string_view name() const { return name_; }
  constexpr operator std::string_view() const { return name_; }
  operator std::string() const { return std::string(name_); }
  friend constexpr bool operator==(ResourceName a, ResourceName b) { return a.name_ == b.name_; }
  friend constexpr bool operator==(ResourceName a, std::string_view b) { return a.name_ == b; }
  friend std::ostream& operator<<(std::ostream& out, ResourceName n) { return out << n.name_; }

 private:
  std::string_view name_;
};

using ImageName = ResourceName<struct ImageKind>;
using BufferName = ResourceName<struct BufferKind>;

}  // namespace tl::graph
