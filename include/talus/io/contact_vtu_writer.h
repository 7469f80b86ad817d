#pragma once

#include <talus/contact/contact_set.h>

#include <string>

namespace talus
{

/// Writes every sub-contact as a point (VTK vertex cell) with the contact's
/// normal, the normal force (N, compression positive), the shear force
/// vector (N), the area (m^2), the state (0 elastic, 1 slipping, 2 open;
/// +4 once failed) and the contact type (index of ContactType). In ParaView,
/// glyphs of "normal force" show how load passes through the blocks.
void write_contacts_vtu(const std::string& path, const ContactSet& contacts);

} // namespace talus
