#pragma once

#include <talus/contact/contact_set.h>
#include <talus/model/block_model.h>

namespace talus
{

/// The joint a contact lies on, as a face origin of BlockModel (the joint
/// set's or single joint's code; 0 when neither face came from a joint, or
/// when its two faces came from different joints). Each side contributes
/// its face turned most towards the other block (within 10 degrees of the
/// common plane; none for a side that touches with a vertex or an edge).
/// For output: it looks at every face of both blocks.
int contact_joint_origin(const BlockModel& model, const ContactSet& contacts, unsigned int c);

} // namespace talus
