"""Networks with weights that look trained, for the tests of devtools/train (which need torch)."""


def trained_looking(net, seed: int = 1):
    """``net`` with non-trivial weights and batch-norm statistics, as a trained network has,
    in eval mode."""
    import torch

    gen = torch.Generator().manual_seed(seed)
    with torch.no_grad():
        for name, value in net.state_dict().items():
            if value.dtype.is_floating_point:
                if name.endswith("running_var"):
                    value.copy_(0.5 + torch.rand(value.shape, generator=gen))
                else:
                    value.copy_(0.2 * torch.randn(value.shape, generator=gen))
    return net.eval()
