#pragma once
// furniture_fem/contact/contact_law_kernel.hpp: a contact law behind one run-time interface, so that
// what applies a law (RoomContact, the Simulation, the scene runner) is compiled once for every law.
//
//   ContactLawKernel            the interface: a contact's force, its slopes and its history, by the law
//   ContactLawKernelOf<Law>     a compile-time law (ContactLaw<Normal, Damping, Friction> or any
//                               ContactLawPolicy) behind it; the law's parts stay inlined in its force
//   make_contact_law_kernel     the shared kernel of a law object
//
// The law's type stops here (issue 48): a law is one indirect call per contact evaluation, its normal,
// damping and friction parts composed and inlined inside it. Measured against the inlined law in
// docs/performance.md section 6.
#include <memory>
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
};

template <class Law>
class ContactLawKernelOf final : public ContactLawKernel {
  static_assert(ContactLawPolicy<Law>,
                "furniture_fem: a contact law must provide force(kinematics, params, state) returning ContactForce "
                "(a const member function taking ContactKinematics, ContactParams and ContactState&); see "
                "docs/contact/contact.md");

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
