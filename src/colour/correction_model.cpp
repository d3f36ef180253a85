// placeholder: filled by the correction_model work
