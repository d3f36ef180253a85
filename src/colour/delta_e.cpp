// placeholder: filled by the delta_e work
