# Empty dependencies file for springlab_rope_reference.
# This may be replaced when dependencies are built.
