# Empty dependencies file for asr_timing.
# This may be replaced when dependencies are built.
