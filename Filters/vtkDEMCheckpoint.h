/**
 * @file vtkDEMCheckpoint.h
 * @brief Resuming a DEM Load Test from its Checkpoint File (not wrapped).
 *
 * A checkpoint (run.rdem) holds the model at one frame of a stage's run. Beside it the
 * stage writes a small record (run.rdem.stage, text) naming the run it belongs to: a
 * fingerprint of the stage's input data and settings, the steps of a frame and the frame
 * saved. A stage that starts with exactly that input and those settings (a reloaded
 * .pvsm, say) takes the frame from the file instead of computing it again: the run is
 * deterministic, so the file's frame is the frame it would compute. A record that does
 * not match (something upstream or a setting changed) is ignored and the file is
 * overwritten when the new run reaches its end.
 */
#ifndef vtkDEMCheckpoint_h
#define vtkDEMCheckpoint_h

#include <cstdint>
#include <string>

class vtkDataObject;

namespace rockdem
{
/// Fingerprint of a stage's run: every value of the input (points and arrays of every
/// block, field data, in order) and a text of the stage's settings (FNV-1a 64).
std::uint64_t RunFingerprint(vtkDataObject* input, const std::string& settings);

/// What the record beside a checkpoint says.
struct CheckpointRecord
{
  std::uint64_t run = 0;         ///< RunFingerprint of the stage that wrote it
  std::int64_t stepsPerFrame = 0; ///< physics steps in one of its frames
  int frame = -1;                ///< the frame the checkpoint holds
  bool finished = false;         ///< the run ended at that frame (test done or settled)
};

/// run.rdem -> run.rdem.stage
std::string CheckpointRecordPath(const std::string& checkpoint);

/// Writes the record (dem::writeFileAtomically: a temporary file renamed over it). Throws
/// naming the file and the reason when it cannot be written.
void WriteCheckpointRecord(const std::string& checkpoint, const CheckpointRecord& record);

/// Reads the record; false when there is none or it is not a record.
bool ReadCheckpointRecord(const std::string& checkpoint, CheckpointRecord& record);
}

#endif
