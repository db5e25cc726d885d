#include <algorithm>
#include <cctype>
#include <map>

#include <fmt/format.h>

#include "machdyn/analysis/topology.hpp"
#include "machdyn/elements/contact.hpp"
#include "machdyn/elements/linearize.hpp"

namespace machdyn {

namespace {

std::string trim(const std::string& s, size_t* lead) {
  size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  if (lead) *lead = b;
  return s.substr(b, e - b);
}

bool gap_word(const std::string& w, GapMode* g) {
  if (w == "open") return *g = GapMode::open, true;
  if (w == "closed" || w == "closed+") return *g = GapMode::closed_pos, true;
  if (w == "closed-") return *g = GapMode::closed_neg, true;
  return false;
}

/// The direction a contact slides in when the topology says only "sliding": slip+, or a
/// freewheel's free direction.
ContactMode free_direction(const FrictionContact& c) {
  return ContactLaw::of(c).can_slide(ContactMode::slip_pos) ? ContactMode::slip_pos : ContactMode::slip_neg;
}

/// Sets mode and engagement from a contact word; false if the word is not one. Besides the
/// contact words, the words of the element's own kind: an end stop is `closed` (at the stop, held:
/// stuck) or `open` (off it: released), as a gap; a freewheel `locked` (stuck) or `free` (sliding
/// in its free direction); a brake `applied` (stuck).
bool contact_word(const std::string& w, const FrictionContact& contact, ContactMode* c, bool* engaged) {
  *engaged = true;
  const bool brake = contact.brake;
  if (contact.stop && (w == "closed" || w == "on")) return *c = ContactMode::stuck, true;
  if (contact.stop && (w == "open" || w == "off")) return *c = ContactMode::stuck, *engaged = false, true;
  if (contact.lock != 0 && w == "locked") return *c = ContactMode::stuck, true;
  if (contact.lock != 0 && w == "free") return *c = free_direction(contact), true;
  if (w == "stuck" || (brake && w == "applied")) return *c = ContactMode::stuck, true;
  if (w == "slip+" || w == "sliding") return *c = ContactMode::slip_pos, true;
  if (w == "slip-") return *c = ContactMode::slip_neg, true;
  if (w == "released") return *c = ContactMode::stuck, *engaged = false, true;
  return false;
}

std::string names_of(const Model& m) {
  std::vector<std::string> n;
  for (const Link& l : m.links)
    if (l.has_gap) n.push_back(l.name);
  for (const FrictionContact& c : m.contacts)
    if (!c.joint) n.push_back(c.name);
  return n.empty() ? "none: the model has no gap, contact or brake" : fmt::format("{}", fmt::join(n, ", "));
}

}  // namespace

void apply_topology_text(const Model& m, const std::string& text, const Location& where, Topology& topo) {
  if (topo.engaged.empty()) topo.engaged.assign(m.contacts.size(), true);
  Diagnostics diag;
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find(',', start);
    if (end == std::string::npos) end = text.size();
    const std::string item = text.substr(start, end - start);
    size_t lead = 0;
    const std::string t = trim(item, &lead);
    const Location at{where.file, where.line > 0 ? where.line : 1, where.column + static_cast<int>(start + lead) + 1};
    const size_t eq = t.find('=');
    if (t.empty()) {
      if (!(start == 0 && end == text.size() && text.find_first_not_of(" \t") == std::string::npos))
        diag.error(at, "an empty entry: expected ELEMENT=MODE");
    } else if (eq == std::string::npos) {
      diag.error(at, fmt::format("'{}': expected ELEMENT=MODE (elements: {})", t, names_of(m)));
    } else {
      const std::string name = trim(t.substr(0, eq), nullptr);
      size_t wlead = 0;
      const std::string word = trim(t.substr(eq + 1), &wlead);
      const Location wat{at.file, at.line, at.column + static_cast<int>(eq + 1 + wlead)};
      const auto link = std::find_if(m.links.begin(), m.links.end(), [&](const Link& l) { return l.name == name; });
      const auto contact =
          std::find_if(m.contacts.begin(), m.contacts.end(), [&](const FrictionContact& c) { return c.name == name; });
      if (link != m.links.end()) {
        GapMode g;
        if (!link->has_gap)
          diag.error(at, fmt::format("link '{}' has no gap, so it has no mode (elements with modes: {})", name,
                                     names_of(m)));
        else if (!gap_word(word, &g))
          diag.error(wat, fmt::format("'{}' is not a mode of gap link '{}': expected open, closed, closed+ or closed-",
                                      word, name));
        else
          topo.gaps[static_cast<size_t>(link - m.links.begin())] = g;
      } else if (contact != m.contacts.end() && contact->joint) {
        diag.error(at, fmt::format("'{}' is a gear joint, always locked: it has no mode (elements with modes: {})",
                                   name, names_of(m)));
      } else if (contact != m.contacts.end()) {
        ContactMode c;
        bool engaged;
        const bool known = contact_word(word, *contact, &c, &engaged);
        if (known && word == "sliding") c = free_direction(*contact);  // a freewheel's free direction
        if (!known) {
          const char* kind = contact->stop ? "end stop" : contact->lock != 0 ? "freewheel" : contact->brake ? "brake" : "contact";
          const char* own = contact->stop ? "closed (at the stop), open (off it), "
                            : contact->lock != 0 ? "locked, free, "
                            : contact->brake ? "applied, " : "";
          diag.error(wat, fmt::format("'{}' is not a mode of {} '{}': expected {}stuck, slip+, slip-, sliding or released",
                                      word, kind, name, own));
        } else {
          const auto k = static_cast<size_t>(contact - m.contacts.begin());
          topo.contacts[k] = c;
          topo.engaged[k] = engaged;
        }
      } else {
        diag.error(at, fmt::format("no gap link, contact or brake '{}' (elements with modes: {})", name, names_of(m)));
      }
    }
    start = end + 1;
  }
  diag.throw_if_any();
}

Topology parse_topology(const Model& m, const std::string& text, const Location& where, double t) {
  Topology topo = initial_topology(m, t);
  apply_topology_text(m, text, where, topo);
  return topo;
}

std::string topology_label(const Model& m, const Topology& topo) {
  std::vector<std::string> parts;
  for (size_t l = 0; l < m.links.size(); ++l)
    if (m.links[l].has_gap) parts.push_back(m.links[l].name + "=" + to_string(topo.gaps[l]));
  for (size_t k = 0; k < m.contacts.size(); ++k) {
    if (m.contacts[k].joint) continue;  // always stuck
    const bool engaged = topo.engaged.empty() || topo.engaged[k];
    parts.push_back(m.contacts[k].name + "=" + (engaged ? to_string(topo.contacts[k]) : "released"));
  }
  return fmt::format("{}", fmt::join(parts, ", "));
}

int switching_elements(const Model& m) {
  int k = 0;
  for (const FrictionContact& c : m.contacts) k += !c.joint;
  for (const Link& l : m.links) k += l.has_gap;
  return k;
}

std::vector<Topology> all_topologies(const Model& m, int max_elements) {
  std::vector<int> gap_links;
  for (size_t l = 0; l < m.links.size(); ++l)
    if (m.links[l].has_gap) gap_links.push_back(static_cast<int>(l));
  const int k = switching_elements(m);
  if (k > max_elements)
    throw InputError(Location{m.source, 0, 0},
                     fmt::format("{} gaps, contacts and brakes give 2^{} topologies (more than 2^{} are not listed): "
                                 "name the modes with --topology ELEMENT=MODE,...",
                                 k, k, max_elements));
  const Topology base = initial_topology(m);
  std::vector<Topology> out;
  for (long bits = 0; bits < (1L << k); ++bits) {
    Topology t = base;
    t.engaged.assign(m.contacts.size(), true);
    int e = 0;
    // Closed and stuck first (bit 0): the stiffest topology leads the list.
    for (int l : gap_links) t.gaps[static_cast<size_t>(l)] = (bits >> e++) & 1 ? GapMode::open : GapMode::closed_pos;
    for (size_t c = 0; c < m.contacts.size(); ++c)
      t.contacts[c] = m.contacts[c].joint ? ContactMode::stuck
                      : (bits >> e++) & 1 ? free_direction(m.contacts[c])
                                          : ContactMode::stuck;
    out.push_back(std::move(t));
  }
  return out;
}

std::vector<TopologyInterval> run_topologies(const Model& m, const HybridReport& report, double t_end) {
  std::map<std::string, int> element;  // gap links: index; contacts: 1000000 + index
  for (size_t l = 0; l < m.links.size(); ++l)
    if (m.links[l].has_gap) element[m.links[l].name] = static_cast<int>(l);
  for (size_t k = 0; k < m.contacts.size(); ++k) element[m.contacts[k].name] = 1000000 + static_cast<int>(k);
  Topology topo = initial_topology(m);
  topo.engaged.assign(m.contacts.size(), true);
  std::vector<bool> released(m.contacts.size(), false);
  auto set = [&](const std::string& name, const std::string& word) {
    const auto it = element.find(name);
    if (it == element.end()) return;
    if (it->second < 1000000) {
      GapMode g;
      if (gap_word(word, &g)) topo.gaps[static_cast<size_t>(it->second)] = g;
      return;
    }
    const auto k = static_cast<size_t>(it->second - 1000000);
    ContactMode c;
    bool engaged;
    if (contact_word(word, m.contacts[k], &c, &engaged)) {
      released[k] = !engaged;
      if (engaged) topo.contacts[k] = c;
    }
  };
  // Switch times: the events and where an application of a brake or clutch changes (it acts while
  // its application is positive).
  std::vector<double> times;
  for (const ModeEvent& e : report.events)
    if (e.kind != "initial") times.push_back(e.t);
  for (const FrictionContact& c : m.contacts)
    for (double t : c.application_times(t_end)) times.push_back(t);
  times.push_back(t_end);
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());

  std::vector<TopologyInterval> out;
  std::map<std::string, size_t> index;
  size_t next_event = 0;
  double t0 = 0.0;
  auto advance_events = [&](double upto) {  // every event at or before `upto`
    while (next_event < report.events.size() && report.events[next_event].t <= upto) {
      const ModeEvent& e = report.events[next_event++];
      set(e.element, e.to);
    }
  };
  advance_events(0.0);
  for (double t1 : times) {
    if (t1 <= t0) continue;
    Topology now = topo;
    for (size_t k = 0; k < m.contacts.size(); ++k) {
      const ContactLaw law = ContactLaw::of(m.contacts[k]);
      const double mid = 0.5 * (t0 + t1);
      now.engaged[k] = !released[k] && !law.released(mid) && law.static_limit(mid) > 0.0;
    }
    const std::string key = topology_label(m, now);
    auto [it, added] = index.try_emplace(key, out.size());
    if (added) out.push_back({now, {}});
    auto& iv = out[it->second].intervals;
    if (!iv.empty() && iv.back().second == t0) iv.back().second = t1;  // the same topology continues
    else iv.emplace_back(t0, t1);
    advance_events(t1);
    t0 = t1;
  }
  return out;
}

}  // namespace machdyn
