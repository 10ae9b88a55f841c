// The byte layout of a v5 MAT-file, checked before libmatio reads it (io/mat_file.cc). libmatio trusts what a file
// declares: a data element cut short comes back zero-filled, and an array whose dimensions claim more values than its
// data element holds is read past its end (values that changed from call to call), cut silently when they claim
// fewer, or allocated whole before anything is read (an 8 KB file that declared 2^31 - 1 samples took 8 GB: the
// twentieth adversarial pass's P1). Here every top-level element must fit in the file, and every numeric or character
// array (also inside structs and cells, and inside compressed elements, inflated under a size limit) must hold
// exactly the bytes its dimensions and its stored type imply (MAT-File Format, The MathWorks, chapter 1).
#pragma once

#include <string>

namespace beamid::io {

// InputError naming the file (`where`, "path: "), the byte offset and the variable on the first violation.
void check_v5_layout(const std::string& where, const std::string& bytes, bool little_endian);

}  // namespace beamid::io
