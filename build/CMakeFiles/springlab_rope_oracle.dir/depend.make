# Empty dependencies file for springlab_rope_oracle.
# This may be replaced when dependencies are built.
