#pragma once
// furniture_fem/contact/contact_law_kernel.hpp: a contact law behind one run-time interface, so that
// what applies a law (RoomContact, the Simulation, the scene runner) is compiled once for every law.
//
//   ContactLawKernel            the interface: a contact's force, its slopes and its history, by the law
//   ContactLawKernelOf<Law>     a compile-time law (ContactLaw<Normal, Damping, Friction> or any
//                               ContactLawPolicy) behind it; the law's parts stay inlined in its force
//   make_contact_law_kernel     the shared kernel of a law object
//   contact_law_parameters<Law> the parameters its parts declare (LawParameter), each once
//
// The law's type stops here (issue 48): a law is one indirect call per contact evaluation, its normal,
// damping and friction parts composed and inlined inside it. Measured against the inlined law in
// docs/performance.md section 6.
#include <array>
#include <cstddef>
#include <memory>
#include <span>
#include <type_traits>
#include <utility>

#include "contact_laws.hpp"

namespace furniture_fem {

// Whether a law keeps a tangential history of its own (a stick spring): its pairs' states must then be
// kept from step to step whatever the scene's stick_length.
template <class Law>
inline constexpr bool contact_law_has_history = false;
template <class Normal, class Damping>
inline constexpr bool contact_law_has_history<ContactLaw<Normal, Damping, StickSlip>> = true;

namespace detail {
template <class Part>
constexpr auto part_parameters() {
  if constexpr (requires { Part::parameters; }) return Part::parameters;
  else return std::array<LawParameter, 0>{};
}
// A composed law's parts' declarations in order (normal, damping, friction), or a law's own `parameters`.
template <class Law>
constexpr auto declared_parameters() {
  if constexpr (requires { typename Law::normal_part_type; }) {
    constexpr auto n = part_parameters<typename Law::normal_part_type>();
    constexpr auto d = part_parameters<typename Law::damping_part_type>();
    constexpr auto f = part_parameters<typename Law::friction_part_type>();
    std::array<LawParameter, n.size() + d.size() + f.size()> all{};
    std::size_t i = 0;
    for (const auto& x : n) all[i++] = x;
    for (const auto& x : d) all[i++] = x;
    for (const auto& x : f) all[i++] = x;
    return all;
  } else {
    return part_parameters<Law>();
  }
}
template <class Law>
constexpr bool first_of_its_kind(std::size_t i) {
  constexpr auto all = declared_parameters<Law>();
  for (std::size_t j = 0; j < i; ++j)
    if (all[j].same_as(all[i])) return false;
  return true;
}
template <class Law>
constexpr std::size_t distinct_count() {
  std::size_t c = 0;
  for (std::size_t i = 0; i < declared_parameters<Law>().size(); ++i) c += first_of_its_kind<Law>(i);
  return c;
}
template <class Law>
constexpr auto distinct_parameters() {
  constexpr auto all = declared_parameters<Law>();
  std::array<LawParameter, distinct_count<Law>()> out{};
  for (std::size_t i = 0, o = 0; i < all.size(); ++i)
    if (first_of_its_kind<Law>(i)) out[o++] = all[i];
  return out;
}
// Whether declarations of one key agree on its unit, range and place (the scene and the docs say one).
template <class Declarations>
constexpr bool keys_agree(const Declarations& all) {
  for (std::size_t i = 0; i < all.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (all[i].key == all[j].key && !all[i].same_key_terms(all[j])) return false;
  return true;
}
}  // namespace detail

// The parameters a law's parts declare, in their order, a declaration two parts share once (the paper's
// q). A key may stand several times when it sets several fields (the anisotropic friction's mu).
template <class Law>
inline constexpr auto contact_law_parameters = detail::distinct_parameters<Law>();

class ContactLawKernel {
 public:
  virtual ~ContactLawKernel() = default;
  // F on A, its slopes K and C, and the advanced state (ContactLawPolicy::force).
  virtual ContactForce force(const ContactKinematics& k, const ContactParams& p, ContactState& state) const = 0;
  // Checks a parameter set against what the law's parts need (ContactParams::validate and the parts').
  virtual void validate(const ContactParams& p) const = 0;
  // The law keeps a tangential history of its own (contact_law_has_history).
  virtual bool has_history() const = 0;
  // Whether the law clamps a pulling total normal force at zero (ContactLaw::clamp_tensile; false for a
  // law without that member).
  virtual bool clamps_tensile() const = 0;
  // The parameters its parts declare (contact_law_parameters), and the per-node ones as a share mask
  // (ContactParams::per_node_mask), for RoomContact to take once.
  virtual std::span<const LawParameter> parameters() const = 0;
  virtual unsigned per_node_mask() const = 0;
};

template <class Law>
class ContactLawKernelOf final : public ContactLawKernel {
  static_assert(ContactLawPolicy<Law>,
                "furniture_fem: a contact law must provide force(kinematics, params, state) returning ContactForce "
                "(a const member function taking ContactKinematics, ContactParams and ContactState&); see "
                "docs/contact/contact.md");
  static_assert(detail::keys_agree(contact_law_parameters<Law>),
                "furniture_fem: two parts of a contact law declare one key with different units, ranges or places");

 public:
  explicit ContactLawKernelOf(Law law = {}) : law_(std::move(law)) {}
  ContactForce force(const ContactKinematics& k, const ContactParams& p, ContactState& state) const override {
    return law_.force(k, p, state);
  }
  void validate(const ContactParams& p) const override {
    if constexpr (requires { Law::validate(p); }) Law::validate(p);
    else p.validate();
  }
  bool has_history() const override { return contact_law_has_history<Law>; }
  bool clamps_tensile() const override {
    if constexpr (requires { law_.clamp_tensile; }) return law_.clamp_tensile;
    else return false;
  }
  std::span<const LawParameter> parameters() const override { return contact_law_parameters<Law>; }
  unsigned per_node_mask() const override { return ContactParams::per_node_mask(contact_law_parameters<Law>); }
  const Law& law() const { return law_; }

 private:
  Law law_;
};

// The kernel of `law`, shared by the copies of what holds it (a kernel is never changed once made).
template <class Law>
std::shared_ptr<const ContactLawKernel> make_contact_law_kernel(Law law = {}) {
  return std::make_shared<const ContactLawKernelOf<std::remove_cvref_t<Law>>>(std::move(law));
}

}  // namespace furniture_fem
